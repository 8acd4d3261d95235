// Scratch: traces bump cases (not committed).
#include <cstdlib>
#include <sstream>
#include <gtest/gtest.h>

#include "vpRigUpdateTestTools.h"

using namespace vpProjectiveTest;

namespace
{
double targetError(const vpServoProjective &task, const ArmSetup &truth, const vpColVector &qTarget)
{
  double sum = 0.0;
  for (size_t k = 0; k < kTracked.size(); ++k) {
    const Eigen::Vector4d e = toEigen4(task.getDesiredFeature(static_cast<unsigned int>(k))) -
                              truth.imageOf(truth.armJoints(qTarget), kTracked[k]);
    sum += e.squaredNorm();
  }
  return std::sqrt(sum / (4.0 * kTracked.size()));
}

// RMS of the task's s* against the ideal re-expression: the old rig's triangulation of the user's s* seen by the true
// bumped cameras (in the model's frame).
double reExpressionError(const vpServoProjective &task, const std::vector<vpFeatureStereoPoint> &userStar,
                         const ArmSetup &s, const ArmSetup &b)
{
  const vpProjectiveStereoRig rig = s.rig();
  const Eigen::Matrix4d H = s.Hpe(rig);
  const Eigen::Matrix4d M = toEigen<4, 4>(b.wMl.inverse() * s.wMl);
  const Eigen::Matrix<double, 3, 4> Pl = toEigen<3, 3>(b.camLeft.get_K()) * (M * H).topRows<3>();
  const Eigen::Matrix<double, 3, 4> Pr = toEigen<3, 3>(b.camRight.get_K()) * (toEigen<4, 4>(b.rMl) * M * H).topRows<3>();
  double sum = 0.0;
  for (size_t k = 0; k < userStar.size(); ++k) {
    const Eigen::Vector4d u = userStar[k].getFeature();
    const Eigen::Vector4d X = rig.triangulate(Eigen::Vector2d(u(0), u(1)), Eigen::Vector2d(u(2), u(3)));
    const Eigen::Vector3d l = Pl * X, r = Pr * X;
    const Eigen::Vector4d ideal(l(0) / l(2), l(1) / l(2), r(0) / r(2), r(1) / r(2));
    sum += (toEigen4(task.getDesiredFeature(static_cast<unsigned int>(k))) - ideal).squaredNorm();
  }
  return std::sqrt(sum / (4.0 * userStar.size()));
}

bool changed(const vpProjectiveStereoRig::Projection &a, const vpProjectiveStereoRig::Projection &b)
{
  const vpProjectiveStereoRig::Projection an = a / a.norm(), bn = b / b.norm();
  return std::min((an - bn).norm(), (an + bn).norm()) > 1e-9;
}
} // namespace

struct TraceOut {
  int detected = -1;
  double re[4] = {0, 0, 0, 0};
  double deg = 0, mm = 0;
  int motion = 0;
};

TraceOut trace(const std::string &arm, long seed, long k, bool twin, bool print)
{
  TraceOut out;
  std::ostringstream devnull;
  std::ostream &os = print ? os : devnull;
  const bool randomRig = k % 2 == 1;
  const ArmSetup s = studySetup(arm, randomRig, static_cast<unsigned int>(seed));
  const BumpKind kind = static_cast<BumpKind>(k % 3);
  const BumpMotion motion = static_cast<BumpMotion>(k / 3 % 3);
  os << s.name << " seed " << seed << " " << bumpName(kind) << " " << bumpMotionName(motion) << std::endl;

  // As runBumpCase with ratios off.
  vpUniRand rng(seed);
  vpGaussRand noise(1.0, 0.0, seed);
  const vpProjectiveRobot acquired = acquiredRobot(s, noise);
  const ArmSetup bb = bumped(s, kind, rng, motion);
  for (int j = 0; j < 10; ++j) {
    visibleJoints({&s, &bb}, rng);
  }
  const vpColVector qTarget = jointsNear({&s, &bb}, rng, vpColVector(s.n(), 0.0), jointBox(s, 20.0));
  const vpColVector qStart = jointsNear({&s, &bb}, rng, qTarget, jointBox(s, 15.0));
  const ArmSetup &b = twin ? s : bb;
  os << "calibration residual " << acquired.getCalibrationResidual() << std::endl;

  const long rs = 7 * seed + 1;
  vpUniRand rrng(rs);
  vpGaussRand rnoise(1.0, 0.0, rs);
  vpProjectiveRobot robot = acquired;
  ServoRun run(s, robot, qTarget, kSigma, rnoise);
  run.task.setRobot(robot);
  os << "s* noise (user s* vs true unbumped at target) " << targetError(run.task, s, qTarget) << " px"
            << std::endl;
  vpColVector q = qStart;
  for (int it = 0; it < 6; ++it) {
    run.step(s, q, kSigma, rnoise);
  }
  // The bump's image motion per feature at q.
  os << "bump image motion per feature (max over images):";
  for (size_t j = 0; j < kTracked.size(); ++j) {
    const Eigen::Vector4d d = b.imageOf(b.armJoints(q), kTracked[j]) - s.imageOf(s.armJoints(q), kTracked[j]);
    os << " " << std::max(d.head<2>().norm(), d.tail<2>().norm());
  }
  os << std::endl;
  for (int it = 1; it <= 4; ++it) {
    const auto st = run.step(b, q, kSigma, rnoise);
    os << "after bump call " << it << " status " << st << " distances:";
    for (unsigned int j = 0; j < kTracked.size(); ++j) {
      os << " " << run.task.getModelMismatch().getDistance(j);
    }
    os << std::endl;
    if (st == vpServoProjective::SERVO_MODEL_MISMATCH) {
      out.detected = it;
      break;
    }
  }
  const vpProjectiveStereoRig::Projection Pl = robot.getModel().getStereoRig().leftProjection(),
                                          Pr = robot.getModel().getStereoRig().rightProjection();
  reRegister(robot, b, 3, rrng, rnoise, q, jointBox(s, 20.0));
  os << "updateRig: residual " << robot.getRigRegistrationResidual() << " left changed "
            << changed(Pl, robot.getModel().getStereoRig().leftProjection()) << " right changed "
            << changed(Pr, robot.getModel().getStereoRig().rightProjection()) << std::endl;
  vpColVector qRest(s.n(), 0.0);
  for (int it = 0; it < 150; ++it) {
    run.step(b, q, kSigma, rnoise);
    if (it == 0 || it == 40 || it == 80 || it == 120) {
      out.re[it / 40] = reExpressionError(run.task, run.sStar, s, b);
    }
    if (it == 0 || it % 40 == 0 || it == 149) {
      double deg, m;
      toolPoseError(s, q, qTarget, deg, m);
      os << "it " << it << " status " << run.task.getStatus() << " s* error (vs true bumped) "
                << targetError(run.task, b, qTarget) << " px, re-expression error "
                << reExpressionError(run.task, run.sStar, s, b) << " px, refinements "
                << run.task.getRigRefinementState().getNumberOfRefinements() << " pose err " << deg << " deg "
                << 1000 * m << " mm, |e| " << run.task.getError().frobeniusNorm() << std::endl;
    }
    if (it >= 120) {
      qRest += q / 30.0;
    }
  }
  double deg, m;
  toolPoseError(s, qRest, qTarget, deg, m);
  os << "final " << deg << " deg " << 1000 * m << " mm" << std::endl;
  out.deg = deg;
  out.mm = 1000 * m;
  out.motion = motion;
  return out;
}

TEST(BumpTrace, Trace)
{
  const char *armEnv = std::getenv("ARM");
  const std::string arm = armEnv ? armEnv : "puma";
  const long seed = std::atol(std::getenv("SEED"));
  const long k = seed - std::atol(std::getenv("SEED0") ? std::getenv("SEED0") : "30000");
  trace(arm, seed, k, std::getenv("TWIN") != nullptr, true);
}

TEST(BumpTrace, Batch)
{
  const char *armEnv = std::getenv("ARM");
  const std::string arm = armEnv ? armEnv : "puma";
  const long seed0 = std::atol(std::getenv("SEED0") ? std::getenv("SEED0") : "30000");
  const int cases = std::atoi(std::getenv("CASES") ? std::getenv("CASES") : "30");
  std::vector<double> re[3][4];
  int fails[3] = {0, 0, 0}, n[3] = {0, 0, 0};
  for (int k = 0; k < cases; ++k) {
    const TraceOut o = trace(arm, seed0 + k, k, std::getenv("TWIN") != nullptr, false);
    for (int j = 0; j < 4; ++j) {
      re[o.motion][j].push_back(o.re[j]);
    }
    ++n[o.motion];
    fails[o.motion] += o.mm > 2.0 || o.deg > 2.0;
    std::cout << "seed " << seed0 + k << " motion " << o.motion << " det " << o.detected << " re " << o.re[0] << " "
              << o.re[1] << " " << o.re[2] << " " << o.re[3] << " final " << o.deg << " deg " << o.mm << " mm"
              << std::endl;
  }
  for (int m = 0; m < 3; ++m) {
    std::cout << "motion " << m << " cases " << n[m] << " fails " << fails[m] << " median re:";
    for (int j = 0; j < 4; ++j) {
      std::cout << " " << median(re[m][j]);
    }
    std::cout << " q90:";
    for (int j = 0; j < 4; ++j) {
      std::cout << " " << quantile(re[m][j], 0.9);
    }
    std::cout << std::endl;
  }
}

namespace
{
struct Stat {
  std::vector<double> med, mn, mx;
  void add(const vpServoProjective &task)
  {
    std::vector<double> d;
    for (unsigned int j = 0; j < task.getNumberOfFeatures(); ++j) {
      const double x = task.getModelMismatch().getDistance(j);
      if (x >= 0) d.push_back(x);
    }
    if (d.size() < 2) return;
    std::sort(d.begin(), d.end());
    med.push_back(d[d.size() / 2]);
    mn.push_back(d.front());
    mx.push_back(d.back());
  }
};
void printQ(const char *name, std::vector<double> x)
{
  if (x.empty()) return;
  std::sort(x.begin(), x.end());
  std::cout << name << " n " << x.size() << " q50 " << x[x.size() / 2] << " q99 " << x[x.size() * 99 / 100]
            << " q999 " << x[std::min(x.size() - 1, x.size() * 999 / 1000)] << " max " << x.back() << " min "
            << x.front() << " q01 " << x[x.size() / 100] << " q05 " << x[x.size() / 20] << std::endl;
}
} // namespace

TEST(BumpTrace, Distances)
{
  const char *armEnv = std::getenv("ARM");
  const std::string arm = armEnv ? armEnv : "puma";
  const long seed0 = std::atol(std::getenv("SEED0") ? std::getenv("SEED0") : "30000");
  const int cases = std::atoi(std::getenv("CASES") ? std::getenv("CASES") : "30");
  Stat unb05, unb1, bump1, bump2, pre;
  for (int k = 0; k < cases; ++k) {
    const long seed = seed0 + k;
    const ArmSetup s = studySetup(arm, k % 2 == 1, static_cast<unsigned int>(seed));
    const BumpKind kind = static_cast<BumpKind>(k % 3);
    const BumpMotion motion = static_cast<BumpMotion>(k / 3 % 3);
    vpUniRand rng(seed);
    vpGaussRand noise(1.0, 0.0, seed);
    const vpProjectiveRobot acquired = acquiredRobot(s, noise);
    const ArmSetup b = bumped(s, kind, rng, motion);
    for (int j = 0; j < 10; ++j) {
      visibleJoints({&s, &b}, rng);
    }
    const vpColVector qTarget = jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), jointBox(s, 20.0));
    const vpColVector qStart = jointsNear({&s, &b}, rng, qTarget, jointBox(s, 15.0));
    for (double sigma : {0.5, 1.0}) {
      ServoRun run(s, acquired, qTarget, sigma, noise);
      vpColVector q = qStart;
      for (int it = 0; it < 150; ++it) {
        run.step(s, q, sigma, noise);
        (sigma == 0.5 ? unb05 : unb1).add(run.task);
      }
    }
    {
      const long rs = 7 * seed + 1;
      vpGaussRand rnoise(1.0, 0.0, rs);
      ServoRun run(s, acquired, qTarget, kSigma, rnoise);
      vpColVector q = qStart;
      for (int it = 0; it < 6; ++it) {
        run.step(s, q, kSigma, rnoise);
        pre.add(run.task);
      }
      run.step(b, q, kSigma, rnoise);
      bump1.add(run.task);
      run.step(b, q, kSigma, rnoise);
      bump2.add(run.task);
    }
  }
  for (auto p : {std::make_pair("unbumped 0.5", &unb05), std::make_pair("unbumped 1", &unb1),
                 std::make_pair("pre-bump", &pre), std::make_pair("bump call 1", &bump1),
                 std::make_pair("bump call 2", &bump2)}) {
    std::cout << p.first << std::endl;
    printQ("  median", p.second->med);
    printQ("  min", p.second->mn);
    printQ("  max", p.second->mx);
  }
}

TEST(BumpTrace, BumpSizes)
{
  const int cases = std::atoi(std::getenv("CASES") ? std::getenv("CASES") : "300");
  for (const char *arm : {"puma", "viper850", "prismatic"}) {
    std::vector<double> med[3], mx[3];
    for (int k = 0; k < cases; ++k) {
      const long seed = 50000 + k;
      const ArmSetup s = studySetup(arm, k % 2 == 1, static_cast<unsigned int>(seed));
      const BumpKind kind = static_cast<BumpKind>(k % 3);
      const BumpMotion motion = static_cast<BumpMotion>(k / 3 % 3);
      vpUniRand rng(seed);
      const ArmSetup b = bumped(s, kind, rng, motion);
      const vpColVector q = jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), jointBox(s, 20.0));
      std::vector<double> d;
      for (size_t j = 0; j < kTracked.size(); ++j) {
        const Eigen::Vector4d e = b.imageOf(b.armJoints(q), kTracked[j]) - s.imageOf(s.armJoints(q), kTracked[j]);
        d.push_back(std::max(e.head<2>().norm(), e.tail<2>().norm()));
      }
      std::sort(d.begin(), d.end());
      med[motion].push_back(d[d.size() / 2]);
      mx[motion].push_back(d.back());
    }
    for (int m = 0; m < 3; ++m) {
      std::cout << arm << " " << bumpMotionName(static_cast<BumpMotion>(m)) << std::endl;
      printQ("  median", med[m]);
      printQ("  max", mx[m]);
    }
  }
}
