/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*
  Tests of vpProjectiveDisplacement, the p-displacement H = H_PE^-1 T H_PE of a rigid motion T (Ruf & Horaud, eqs.
  (10)-(12), (21)), against the metric simulator:
  - estimate() from projective points and from images equals H_PE^-1 T_l H_PE normalised by (12), for rotations about
    a general axis, general screw motions, pure translations and no motion; getRotationAngle() is the metric angle and
    classify() tells the kind of motion;
  - the normalisation (12) removes any scale and sign and gives det H = 1; composition and inverse follow the metric
    ones;
  - with 0.5 px noise on 7 markers, the angle and matrix errors stay within bounds derived below, and the Ceres
    (maximum-likelihood) estimate from images is on average no worse than the linear one from triangulated points;
  - every degenerate or invalid input throws a vpProjectiveException with a meaningful code and message.

  Noise-free bounds (1e-8 relative, 1e-8 rad) leave orders of magnitude above rounding for any modelling error; the
  noisy bounds are explained at the test.
*/

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.5; // pixel noise of the noisy test (px)

// A rigid body: n random points in a cube of half side halfSide around the fixation point, pairwise at least
// minDistance apart.
std::vector<vpColVector> rigidBody(const Scene &scene, vpUniRand &rng, size_t n, double halfSide, double minDistance)
{
  std::vector<vpColVector> body;
  while (body.size() < n) {
    const vpColVector X = randomVisiblePoints(scene.sim, rng, Scene::fixation(), halfSide, 1, 20.0)[0];
    bool farEnough = true;
    for (const vpColVector &Y : body) {
      farEnough = farEnough && (X - Y).frobeniusNorm() >= minDistance;
    }
    if (farEnough) {
      body.push_back(X);
    }
  }
  return body;
}

vpColVector centroid(const std::vector<vpColVector> &points)
{
  vpColVector c(3, 0.0);
  for (const vpColVector &X : points) {
    c += X;
  }
  return c / static_cast<double>(points.size());
}

enum MotionKind { Rotation, Screw, Translation, NoMotion };

const char *kindName(MotionKind k)
{
  static const char *names[] = {"rotation", "screw", "translation", "identity"};
  return names[k];
}

/*
  A random motion of the given kind that keeps every point of the body visible (10 px margin): a rotation by theta
  about a random axis through a point within 3 cm of the centroid; the same followed by 3 cm along the axis (a screw);
  a translation by 5 cm along a random direction; the identity.
*/
vpHomogeneousMatrix randomMotion(const Scene &scene, vpUniRand &rng, const std::vector<vpColVector> &body,
                                 MotionKind kind, double theta)
{
  const vpColVector c = centroid(body);
  for (;;) {
    const vpColVector axis = randomDirection(rng);
    const vpColVector p = c + point3(rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03));
    vpHomogeneousMatrix T;
    switch (kind) {
    case Rotation:
      T = vpSimulatorStereoRig::rotationAbout(p, axis, theta);
      break;
    case Screw:
      T = vpSimulatorStereoRig::translationAlong(axis, 0.03) * vpSimulatorStereoRig::rotationAbout(p, axis, theta);
      break;
    case Translation:
      T = vpSimulatorStereoRig::translationAlong(axis, 0.05);
      break;
    case NoMotion:
      break;
    }
    bool visible = true;
    for (const vpColVector &X : vpSimulatorStereoRig::transform(T, body)) {
      visible = visible && scene.sim.isVisible(X, 10.0);
    }
    if (visible) {
      return T;
    }
  }
}

// Images of the body before and after the motion, and their triangulations with the scene's rig.
struct Observation {
  std::vector<vpImagePoint> left0, right0, left1, right1;
  std::vector<vpColVector> M0, M1;
};

Observation observe(const Scene &scene, const std::vector<vpColVector> &body, const vpHomogeneousMatrix &T,
                    double sigma, vpGaussRand &noise)
{
  Observation o;
  scene.sim.project(body, o.left0, o.right0, sigma, noise);
  scene.sim.project(vpSimulatorStereoRig::transform(T, body), o.left1, o.right1, sigma, noise);
  for (size_t j = 0; j < body.size(); ++j) {
    o.M0.push_back(scene.rig.triangulate(o.left0[j], o.right0[j]));
    o.M1.push_back(scene.rig.triangulate(o.left1[j], o.right1[j]));
  }
  return o;
}

// The truth the estimates are compared with, as the work order states it: vpProjectiveDisplacement(H_PE^-1 T_l H_PE).
Eigen::Matrix4d truth(const Scene &scene, const vpHomogeneousMatrix &T)
{
  return vpProjectiveDisplacement(scene.projectiveDisplacement(T)).matrix();
}

double rotationAngle(const vpHomogeneousMatrix &T)
{
  return vpThetaUVector(T.getRotationMatrix()).getTheta();
}

std::vector<vpColVector> projectivePoints(const Scene &scene, const std::vector<vpColVector> &wX)
{
  std::vector<vpColVector> M;
  for (const vpColVector &X : wX) {
    M.push_back(toVispVector(scene.projectivePoint(X)));
  }
  return M;
}
} // namespace

// ---------------------------------------------------------------------------------------------------------------
// Noise-free estimation
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, EstimateNoiseFreeEqualsTruth)
{
  const Scene scene;
  const vpProjectiveDisplacement::vpMotionType expected[] = {
      vpProjectiveDisplacement::ROTATION, vpProjectiveDisplacement::GENERAL, vpProjectiveDisplacement::TRANSLATION,
      vpProjectiveDisplacement::IDENTITY};
  for (int k = Rotation; k <= NoMotion; ++k) {
    const MotionKind kind = static_cast<MotionKind>(k);
    for (unsigned int seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(::testing::Message() << kindName(kind) << ", seed " << seed);
      vpUniRand rng(1000 * (k + 1) + seed);
      vpGaussRand noise(1.0, 0.0, 1);
      // 5 (the minimum) to 9 points.
      const std::vector<vpColVector> body = rigidBody(scene, rng, 4 + seed, 0.08, 0.03);
      const double theta = rng.uniform(0.2, 1.0);
      const vpHomogeneousMatrix T = randomMotion(scene, rng, body, kind, theta);
      const Observation o = observe(scene, body, T, 0.0, noise);
      const Eigen::Matrix4d Htrue = truth(scene, T);

      const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(o.M0, o.M1);
      EXPECT_LT(relativeError(D.matrix(), Htrue), 1e-8);
      const vpProjectiveDisplacement Di =
          vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1);
      EXPECT_LT(relativeError(Di.matrix(), Htrue), 1e-8);

      // The angle of (21) is the metric one; translations and the identity have angle 0 (acos near 1 loses half
      // the digits: 1e-6).
      const double metricAngle = rotationAngle(T);
      const double angleTolerance = (kind == Rotation || kind == Screw) ? 1e-8 : 1e-6;
      EXPECT_NEAR(D.getRotationAngle(), metricAngle, angleTolerance);
      EXPECT_NEAR(Di.getRotationAngle(), metricAngle, angleTolerance);

      EXPECT_EQ(D.classify(), expected[k]);
      EXPECT_EQ(Di.classify(), expected[k]);
      EXPECT_EQ(vpProjectiveDisplacement(Htrue).classify(), expected[k]);
    }
  }
}

TEST(vpProjectiveDisplacement, EstimateFromExactProjectivePoints)
{
  // The true projective points H_PE^-1 N, not triangulated, and with arbitrary scales and signs: M ~ H M0 is a
  // relation between projective points, so the scale of each M must not matter.
  const Scene scene;
  vpUniRand rng(77);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.6);
  std::vector<vpColVector> M0 = projectivePoints(scene, body);
  std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
  for (size_t j = 0; j < M0.size(); ++j) {
    M0[j] *= rng.uniform(-3.0, 3.0);
    M1[j] *= rng.uniform(-3.0, 3.0);
  }
  const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(M0, M1);
  EXPECT_LT(relativeError(D.matrix(), truth(scene, T)), 1e-8);
  EXPECT_LT((D.getMatrix() - toVisp(D.matrix())).frobeniusNorm(), 1e-15);
}

/*
  The minimal case, 5 points, on a small object: 5 random points in a 4 cm cube 1 m away are in general position
  (no 4 coplanar, with probability 1), so the estimate must succeed and be exact. In the rig's frame the unit
  projective points of a small object are nearly parallel, which is a matter of conditioning (the estimator whitens
  its points), not a degeneracy.
*/
TEST(vpProjectiveDisplacement, EstimateMinimalFivePointsOnSmallObject)
{
  const Scene scene;
  for (unsigned int seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(500 + seed);
    const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.02, 5);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.5);
    const std::vector<vpColVector> M0 = projectivePoints(scene, body);
    const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
    try {
      EXPECT_LT(relativeError(vpProjectiveDisplacement::estimate(M0, M1).matrix(), truth(scene, T)), 1e-6);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimate() rejected 5 points in general position: " << e.getStringMessage();
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Normalisation, composition, inverse
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, NormalisationRemovesScaleAndSign)
{
  const Scene scene;
  vpUniRand rng(5);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  for (int k = Rotation; k <= Translation; ++k) {
    SCOPED_TRACE(kindName(static_cast<MotionKind>(k)));
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, static_cast<MotionKind>(k), 0.7);
    // H_PE with an arbitrary scale: the conjugate does not depend on it, and with det H_PE = +-1 from the simulator
    // it is exactly the normalised displacement (det 1, positive trace).
    const Eigen::Matrix4d Hpe = 3.7 * scene.Hpe;
    const Eigen::Matrix4d H = Hpe.inverse() * scene.cameraDisplacement(T) * Hpe;
    const Eigen::Matrix4d Hn = vpProjectiveDisplacement::normalize(H);
    EXPECT_NEAR(Hn.determinant(), 1.0, 1e-12);
    EXPECT_GT(Hn.trace(), 0.0);
    EXPECT_LT(relativeError(Hn, H), 1e-12);
    for (double s : {-5.0, 1e-3, -1e4, 7.5, -1.0}) {
      SCOPED_TRACE(::testing::Message() << "scale " << s);
      const Eigen::Matrix4d Hs = vpProjectiveDisplacement::normalize(Eigen::Matrix4d(s * H));
      EXPECT_LT(relativeError(Hs, Hn), 1e-13);
      EXPECT_NEAR(Hs.determinant(), 1.0, 1e-12);
      // The constructors normalise too.
      EXPECT_LT(relativeError(vpProjectiveDisplacement(toVisp(Eigen::Matrix4d(s * H))).matrix(), Hn), 1e-13);
      EXPECT_LT(relativeError(vpProjectiveDisplacement(Eigen::Matrix4d(s * H)).matrix(), Hn), 1e-13);
    }
  }
  // A rotation close to pi has a trace close to 0 (2 + 2 cos theta): the sign is still found.
  const vpHomogeneousMatrix T = vpSimulatorStereoRig::rotationAbout(Scene::fixation(), point3(0.3, 1.0, 0.2), 3.0);
  const Eigen::Matrix4d H = scene.projectiveDisplacement(T);
  EXPECT_LT(relativeError(vpProjectiveDisplacement::normalize(Eigen::Matrix4d(-2.0 * H)), H), 1e-12);
  EXPECT_NEAR(vpProjectiveDisplacement(H).getRotationAngle(), 3.0, 1e-9);
}

TEST(vpProjectiveDisplacement, CompositionAndInverseFollowTheMetricOnes)
{
  const Scene scene;
  vpUniRand rng(9);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T1 = randomMotion(scene, rng, body, Screw, 0.4);
  const vpHomogeneousMatrix T2 = randomMotion(scene, rng, body, Rotation, 0.9);
  const vpProjectiveDisplacement D1(truth(scene, T1)), D2(truth(scene, T2));
  // Points move by T1 then T2: T2 T1.
  EXPECT_LT(relativeError((D2 * D1).matrix(), truth(scene, T2 * T1)), 1e-10);
  EXPECT_LT(relativeError(D1.inverse().matrix(), truth(scene, T1.inverse())), 1e-10);
  EXPECT_LT(((D1 * D1.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-10);
  EXPECT_EQ((D1 * D1.inverse()).classify(), vpProjectiveDisplacement::IDENTITY);
  // The default displacement is the identity.
  EXPECT_EQ(vpProjectiveDisplacement().matrix(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(vpProjectiveDisplacement().classify(), vpProjectiveDisplacement::IDENTITY);
  EXPECT_EQ(vpProjectiveDisplacement().getRotationAngle(), 0.0);
}

// ---------------------------------------------------------------------------------------------------------------
// Noisy estimation
// ---------------------------------------------------------------------------------------------------------------

/*
  7 markers pairwise >= 8 cm apart in a 20 cm cube 1 m in front of the paper's rig, a 30 deg rotation about a random
  axis through their centroid (+- 3 cm), 0.5 px noise on all four images, the true F (so that the truth is exact),
  20 seeds. Two estimates: linear (DLT on the triangulated points) and maximum likelihood (Ceres, from the images).

  First-order sizes. A marker's stereo depth has std sigma_Z = Z^2 sqrt(2) sigma / (f b) = 0.71 / (1667 * 0.2) =
  2.1 mm (lateral: Z sigma / f = 0.3 mm). Measured over 400 seeds offline (20-seed blocks: worst block mean):
  - angle: a rotation read off 7 points at a lever of ~7 cm has sigma_theta ~ sigma_Z / (7 cm sqrt(7)) = 0.011 rad,
    i.e. a mean |error| of ~0.8 sigma_theta = 0.009 rad. Measured ML: RMS 0.0100, mean 0.0075 (worst block 0.0096),
    max 0.042 rad; linear: mean 0.0098 (worst block 0.0158), max 0.121 rad (the algebraic estimator has a heavy
    tail). Bounds: ML mean 1.3 sigma_theta = 0.015, max 4.5 sigma_theta = 0.051; linear mean 0.025, max 0.15.
  - transfer error: RMS distance (mm) between the true markers moved by H_PE H H_PE^-1 and by the true motion. Both
    point sets are noisy (sqrt(2) sigma_Z) and 15 parameters are fitted on 21 coordinates, so ~ sqrt(2 * 15/21)
    sigma_Z = 2.5 mm. Measured ML mean 2.24 (worst block 2.52), max 5.0 mm; linear mean 2.90 (worst block 3.23), max
    7.1 mm. Bounds: ML mean 1.5 sigma_Z, max 3.5 sigma_Z; linear mean 2 sigma_Z, max 5 sigma_Z.
  - relative matrix error in the markers' whitened frame (W H W^-1, W the whitening of the true points M0, the frame
    the estimator itself works in): ~ sigma_Z / (10 cm spread) = 0.02. Measured ML mean 0.022 (worst block 0.027),
    max 0.079; linear mean 0.030 (worst block 0.035), max 0.117. Bounds: ML mean 0.04, max 0.12; linear mean 0.05,
    max 0.18.
  - relative matrix error in the rig's frame, |H - Htrue|_F / |Htrue|_F: dominated by the entries that the pixel-based
    frame scales up, it has a heavy tail (max over 400 seeds 1.34 ML, 1.93 linear) and only its mean is bounded:
    measured ML mean 0.084 (worst block 0.146), linear 0.224 (worst block 0.31); bounds 0.3 and 0.6.
  The ML estimate must be no worse than the linear one on average, for every measure (it was better in every one of
  the 20 offline blocks for the transfer and whitened errors).
*/
TEST(vpProjectiveDisplacement, EstimateNoisyWithinBounds)
{
  const Scene scene;
  const double theta = vpMath::rad(30.0);
  const double sigmaZ = std::sqrt(2.0) * kSigma / (scene.sim.getLeftCameraParameters().get_px() * 0.20); // Z = 1 m
  const double sigmaTheta = sigmaZ / (0.07 * std::sqrt(7.0));
  const int seeds = 20;
  enum { Angle, Transfer, Whitened, Raw, Measures };
  const char *names[Measures] = {"angle (rad)", "transfer (mm)", "whitened relative", "rig-frame relative"};
  double mean[2][Measures] = {{0.0}}, worst[2][Measures] = {{0.0}};
  for (int seed = 1; seed <= seeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(static_cast<uint64_t>(300 + seed));
    vpGaussRand noise(1.0, 0.0, 300 + seed);
    const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.10, 0.08);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, theta);
    const Observation o = observe(scene, body, T, kSigma, noise);
    const Eigen::Matrix4d Htrue = truth(scene, T);
    const Eigen::Matrix4d Tl = scene.cameraDisplacement(T);
    // Whitening of the true points: W = (sum u u^T / n)^(-1/2), u the unit projective points.
    Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
    for (const vpColVector &X : body) {
      const Eigen::Vector4d u = scene.projectivePoint(X);
      C += u * u.transpose() / static_cast<double>(body.size());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
    const Eigen::Matrix4d W =
        eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();

    const vpProjectiveDisplacement estimates[2] = {
        vpProjectiveDisplacement::estimate(o.M0, o.M1),
        vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1)};
    for (int k = 0; k < 2; ++k) {
      const Eigen::Matrix4d &H = estimates[k].matrix();
      const Eigen::Matrix4d Tm = scene.Hpe * H * scene.HpeInv;
      double transfer = 0.0;
      for (const vpColVector &X : body) {
        const Eigen::Vector4d N0 = scene.cameraPoint(X);
        const Eigen::Vector4d a = Tm * N0, b = Tl * N0;
        transfer += (a.head<3>() / a(3) - b.head<3>()).squaredNorm() / static_cast<double>(body.size());
      }
      const double e[Measures] = {
          std::abs(estimates[k].getRotationAngle() - theta), 1000.0 * std::sqrt(transfer),
          relativeError(Eigen::Matrix4d(W * H * W.inverse()), Eigen::Matrix4d(W * Htrue * W.inverse())),
          relativeError(H, Htrue)};
      for (int m = 0; m < Measures; ++m) {
        mean[k][m] += e[m] / seeds;
        worst[k][m] = std::max(worst[k][m], e[m]);
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    std::cout << "[ stats    ] displacement, 7 markers, 30 deg, sigma " << kSigma << " px, " << seeds << " seeds, "
              << (k == 0 ? "linear" : "ML") << ":";
    for (int m = 0; m < Measures; ++m) {
      std::cout << " " << names[m] << " mean " << mean[k][m] << " max " << worst[k][m] << ";";
    }
    std::cout << std::endl;
  }
  const double sigmaZmm = 1000.0 * sigmaZ;
  // Linear estimate.
  EXPECT_LT(mean[0][Angle], 0.025);
  EXPECT_LT(worst[0][Angle], 0.15);
  EXPECT_LT(mean[0][Transfer], 2.0 * sigmaZmm);
  EXPECT_LT(worst[0][Transfer], 5.0 * sigmaZmm);
  EXPECT_LT(mean[0][Whitened], 0.05);
  EXPECT_LT(worst[0][Whitened], 0.18);
  EXPECT_LT(mean[0][Raw], 0.6);
  // Maximum likelihood.
  EXPECT_LT(mean[1][Angle], 1.3 * sigmaTheta);
  EXPECT_LT(worst[1][Angle], 4.5 * sigmaTheta);
  EXPECT_LT(mean[1][Transfer], 1.5 * sigmaZmm);
  EXPECT_LT(worst[1][Transfer], 3.5 * sigmaZmm);
  EXPECT_LT(mean[1][Whitened], 0.04);
  EXPECT_LT(worst[1][Whitened], 0.12);
  EXPECT_LT(mean[1][Raw], 0.3);
  // The ML estimate is on average no worse than the linear one.
  for (int m = 0; m < Measures; ++m) {
    EXPECT_LE(mean[1][m], mean[0][m]) << names[m];
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, EstimateFromPointsInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(13);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const std::vector<vpColVector> M0 = projectivePoints(scene, body);
  const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));

  const std::vector<vpColVector> M0four(M0.begin(), M0.begin() + 4), M1four(M1.begin(), M1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0four, M1four); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  const std::vector<vpColVector> M1short(M1.begin(), M1.begin() + 7);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, M1short); },
                               vpProjectiveException::dimensionError, "matched pairs"));

  std::vector<vpColVector> bad = M0;
  bad[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M1;
  bad[4][3] = -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, bad); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M0;
  bad[1] = point3(1.0, 2.0, 3.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::dimensionError, "must have 4 entries"));
  bad = M0;
  bad[0] = vpColVector(4, 0.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::invalidValueError, "zero vector"));

  // 5 points, 4 of them on one world plane (hence on one projective plane).
  const vpColVector c = Scene::fixation();
  std::vector<vpColVector> five = {c + point3(0.05, 0.0, 0.01), c + point3(-0.04, 0.03, -0.02),
                                   c + point3(0.01, -0.05, 0.03), c + point3(-0.03, -0.02, -0.01),
                                   c + point3(0.0, 0.0, 0.0)};
  // Put the 4th on the plane of the first three.
  {
    const Eigen::Vector3d a(five[0][0], five[0][1], five[0][2]), b(five[1][0], five[1][1], five[1][2]),
        d(five[2][0], five[2][1], five[2][2]);
    const Eigen::Vector3d q = a + 0.3 * (b - a) + 0.4 * (d - a);
    five[3] = point3(q(0), q(1), q(2));
  }
  const vpHomogeneousMatrix T5 = randomMotion(scene, rng, five, Rotation, 0.5);
  const std::vector<vpColVector> P0 = projectivePoints(scene, five);
  const std::vector<vpColVector> P1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T5, five));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(P0, P1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));
  // A repeated point among 5.
  std::vector<vpColVector> R0 = projectivePoints(scene, std::vector<vpColVector>(body.begin(), body.begin() + 5));
  std::vector<vpColVector> R1 = std::vector<vpColVector>(M1.begin(), M1.begin() + 5);
  R0[4] = R0[1];
  R1[4] = R1[1];
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(R0, R1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));

  // All 8 points on one plane.
  std::vector<vpColVector> planar;
  while (planar.size() < 8) {
    const double x = rng.uniform(-0.08, 0.08), y = rng.uniform(-0.08, 0.08);
    planar.push_back(c + point3(x, y, 0.5 * x + 0.2 * y));
  }
  const std::vector<vpColVector> Q0 = projectivePoints(scene, planar);
  const std::vector<vpColVector> Q1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, planar));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(Q0, Q1); },
                               vpProjectiveException::degenerateConfigurationError, "are coplanar"));
}

TEST(vpProjectiveDisplacement, EstimateFromImagesInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(17);
  vpGaussRand noise(1.0, 0.0, 17);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const Observation o = observe(scene, body, T, 0.0, noise);

  const vpProjectiveStereoRig empty;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(empty, o.left0, o.right0, o.left1, o.right1); },
                               vpProjectiveException::notInitializedError, "no fundamental matrix"));
  const std::vector<vpImagePoint> short1(o.right1.begin(), o.right1.begin() + 5);
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, short1); },
                       vpProjectiveException::dimensionError, "same size"));
  const std::vector<vpImagePoint> l0(o.left0.begin(), o.left0.begin() + 4), r0(o.right0.begin(), o.right0.begin() + 4),
      l1(o.left1.begin(), o.left1.begin() + 4), r1(o.right1.begin(), o.right1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, l0, r0, l1, r1); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  std::vector<vpImagePoint> bad = o.left1;
  bad[3].set_i(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, bad, o.right1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
}

TEST(vpProjectiveDisplacement, InvalidMatricesThrow)
{
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(H); },
                               vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement D(H); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(toVisp(H)); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(3, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(4, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(Eigen::Matrix4d::Zero()); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  Eigen::Matrix4d singular = Eigen::Matrix4d::Identity();
  singular(3, 3) = 0.0;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
}
