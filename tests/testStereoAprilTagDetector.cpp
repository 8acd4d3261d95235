/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 * Copyright (C) 2026 The visp_projective authors.
 *
 * This software is free software; you can redistribute it and/or modify it under the terms of the GNU General Public
 * License as published by the Free Software Foundation; either version 2 of the License, or (at your option) any
 * later version. See the file LICENSE at the root directory of this source distribution.
 *
 * This software is distributed in the hope that it will be useful, but WITHOUT ANY WARRANTY; without even the
 * implied warranty of MERCHANTABILITY or FITNESS FOR A PARTICULAR PURPOSE. See the GNU General Public License for
 * more details.
 */

/*
  Tests of vpSimulatorTagRenderer and vpStereoAprilTagDetector: every rendered 36h11 code is decoded by
  vpDetectorAprilTag as its id (the renderer's table), vpDetectorAprilTag's corner order and half-pixel offset, the
  stereo detector's corners against the exact projections (noise, blur, lighting, decimation, tags on a tool cube),
  pairing and ordering,
  the epipolar check, tracking in predicted regions, occlusion, and the rejection of bad input.
*/

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRxyzVector.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpSimulatorTagRenderer.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>
#if defined(VISP_HAVE_APRILTAG)
#include <visp3/detection/vpDetectorAprilTag.h>
#endif

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_APRILTAG)

namespace
{

const vpSimulatorStereoRig kRig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);

/*
  Tags of 4 cm on a 3 x 2 grid 9 cm x 10 cm around the fixation (1 m from the rig, about 67 px wide), each tilted by
  up to 0.6 rad about x and y, turned by any angle about its normal, moved by up to 5 cm in depth; ids firstId,
  firstId + 1, ...
*/
void addRandomTags(vpSimulatorTagRenderer &renderer, long seed, int firstId, int count = 6)
{
  vpUniRand rnd(seed);
  for (int n = 0; n < count; ++n) {
    const int a = n % 3, b = (n / 3) % 2;
    const double tuz = rnd.uniform(-M_PI, M_PI); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double tuy = rnd.uniform(-0.6, 0.6);
    const double tux = rnd.uniform(-0.6, 0.6);
    const double tz = rnd.uniform(-0.05, 0.05);
    const double dx = rnd.uniform(-0.01, 0.01);
    const vpHomogeneousMatrix wMt(-0.09 + 0.09 * a + dx, -0.05 + 0.1 * b, tz, tux, tuy, tuz);
    renderer.addTag(firstId + n, 0.04, wMt);
  }
}

//! The paper's rig seeing random tags (addRandomTags() from \e seed, ids from \e firstId): the renderer, seeded with
//! \e seed too, and the stereo pair it renders.
vpSimulatorTagRenderer renderRandomTags(long seed, int firstId, vpImage<unsigned char> &Il, vpImage<unsigned char> &Ir)
{
  vpSimulatorTagRenderer renderer(kRig, seed);
  addRandomTags(renderer, seed, firstId);
  renderer.render(Il, Ir);
  return renderer;
}

//! Index of the tag of id \e id in \e renderer (-1 if none).
int indexOf(const vpSimulatorTagRenderer &renderer, int id)
{
  for (unsigned int k = 0; k < renderer.getNbTags(); ++k) {
    if (renderer.getTagId(k) == id) {
      return static_cast<int>(k);
    }
  }
  return -1;
}

//! Sum of squared distances of the detector's corners to the renderer's truth, and their number (both images).
void accumulateErrors(const vpSimulatorTagRenderer &renderer, const vpStereoAprilTagDetector &detector, double &sum2,
                      unsigned int &count, double &worst)
{
  const std::vector<int> &ids = detector.getIds();
  for (size_t k = 0; k < ids.size(); ++k) {
    const int index = indexOf(renderer, ids[k] / 4);
    ASSERT_GE(index, 0) << "detected a tag that was not rendered: id " << ids[k] / 4;
    std::vector<vpImagePoint> left, right;
    ASSERT_TRUE(renderer.getImageCorners(static_cast<unsigned int>(index), left, right));
    const double el = vpImagePoint::distance(detector.getLeftPoints()[k], left[static_cast<size_t>(ids[k] % 4)]);
    const double er = vpImagePoint::distance(detector.getRightPoints()[k], right[static_cast<size_t>(ids[k] % 4)]);
    sum2 += el * el + er * er;
    count += 2;
    worst = std::max(worst, std::max(el, er));
  }
}

} // namespace

// The renderer's table: each of the 32 codes, rendered, is decoded by vpDetectorAprilTag as that id in both images,
// and nothing else is decoded.
TEST(SimulatorTagRenderer, EveryCodeIsDecodedAsItsId)
{
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  for (int first = 0; first <= vpSimulatorTagRenderer::maxTagId; first += 6) {
    vpSimulatorTagRenderer renderer(kRig, first + 1);
    addRandomTags(renderer, first + 1, first, std::min(6, vpSimulatorTagRenderer::maxTagId + 1 - first));
    vpImage<unsigned char> Il, Ir;
    renderer.render(Il, Ir);
    for (const vpImage<unsigned char> *I : {&Il, &Ir}) {
      detector.detect(*I);
      std::vector<int> found = detector.getTagsId(), expected;
      for (unsigned int k = 0; k < renderer.getNbTags(); ++k) {
        expected.push_back(renderer.getTagId(k));
      }
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << "tags " << first << " to " << first + 5;
    }
  }
}

// vpDetectorAprilTag's corner k is the renderer's corner k (the tag frame's (-s/2, s/2), (s/2, s/2), (s/2, -s/2),
// (-s/2, -s/2)), half a pixel off on both axes: AprilTag's pixel centres are at (j + 1/2, i + 1/2).
TEST(StereoAprilTagDetector, ViSPCornerOrderAndHalfPixelOffset)
{
  vpImage<unsigned char> Il, Ir;
  vpSimulatorTagRenderer renderer = renderRandomTags(3, 0, Il, Ir);
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  detector.detect(Il);
  const std::vector<int> ids = detector.getTagsId();
  const std::vector<std::vector<vpImagePoint>> corners = detector.getTagsCorners();
  ASSERT_EQ(ids.size(), 6u);
  double du = 0.0, dv = 0.0, spread = 0.0;
  for (size_t d = 0; d < ids.size(); ++d) {
    std::vector<vpImagePoint> left, right;
    ASSERT_TRUE(renderer.getImageCorners(static_cast<unsigned int>(indexOf(renderer, ids[d])), left, right));
    for (size_t k = 0; k < 4; ++k) {
      du += corners[d][k].get_u() - left[k].get_u();
      dv += corners[d][k].get_v() - left[k].get_v();
      spread = std::max(spread, vpImagePoint::distance(corners[d][k], left[k] + vpImagePoint(0.5, 0.5)));
    }
  }
  EXPECT_NEAR(du / 24.0, 0.5, 0.05);
  EXPECT_NEAR(dv / 24.0, 0.5, 0.05);
  EXPECT_LT(spread, 0.6); // each corner is the right one: the next corner is a tag side (> 40 px) away
}

// At the default settings (noise 1 grey level, no blur), over 6 seeds of 6 random poses: the bound is 0.15 px
// RMS; measured 0.035 px RMS, worst corner 0.15 px.
TEST(StereoAprilTagDetector, CornersWithinATenthOfAPixel)
{
  double sum2 = 0.0, worst = 0.0;
  unsigned int count = 0;
  for (long seed = 1; seed <= 6; ++seed) {
    vpImage<unsigned char> Il, Ir;
    vpSimulatorTagRenderer renderer = renderRandomTags(seed, static_cast<int>(seed), Il, Ir);
    vpStereoAprilTagDetector detector(vpDetectorAprilTag::TAG_36h11);
    EXPECT_EQ(detector.detect(Il, Ir), 24u) << "seed " << seed;
    accumulateErrors(renderer, detector, sum2, count, worst);
  }
  ASSERT_GT(count, 0u);
  EXPECT_LT(std::sqrt(sum2 / count), 0.06);
  EXPECT_LT(worst, 0.25);
}

// The refinement is what makes them accurate: without it (and without AprilTag's own edge refinement), the same
// images give corners several times worse (measured 0.19 px RMS against 0.034 px).
TEST(StereoAprilTagDetector, RefinementImprovesTheCorners)
{
  double rms[2];
  for (int refine = 0; refine < 2; ++refine) {
    double sum2 = 0.0, worst = 0.0;
    unsigned int count = 0;
    for (long seed = 1; seed <= 3; ++seed) {
      vpImage<unsigned char> Il, Ir;
      vpSimulatorTagRenderer renderer = renderRandomTags(seed, 0, Il, Ir);
      vpStereoAprilTagDetector detector;
      detector.setRefinement(refine == 1);
      detector.detect(Il, Ir);
      accumulateErrors(renderer, detector, sum2, count, worst);
    }
    rms[refine] = std::sqrt(sum2 / count);
  }
  EXPECT_LT(rms[1], 0.5 * rms[0]);
}

// With 1 px of optical blur and a lighting change (gain 0.6, offset 20, gradients 30 % and -20 % across the image),
// and with the quads searched at half resolution: measured 0.020 px RMS, worst corner 0.10 px.
TEST(StereoAprilTagDetector, CornersUnderBlurLightingAndDecimation)
{
  for (double decimation : {1.0, 2.0}) {
    double sum2 = 0.0, worst = 0.0;
    unsigned int count = 0;
    for (long seed = 11; seed <= 14; ++seed) {
      vpSimulatorTagRenderer renderer(kRig, seed);
      renderer.setBlur(1.0);
      renderer.setLighting(0.6, 20.0, 0.3, -0.2);
      addRandomTags(renderer, seed, 2);
      vpImage<unsigned char> Il, Ir;
      renderer.render(Il, Ir);
      vpStereoAprilTagDetector detector;
      detector.setDecimation(decimation);
      EXPECT_EQ(detector.detect(Il, Ir), 24u) << "seed " << seed << ", decimation " << decimation;
      accumulateErrors(renderer, detector, sum2, count, worst);
    }
    EXPECT_LT(std::sqrt(sum2 / count), 0.05) << "decimation " << decimation;
    EXPECT_LT(worst, 0.2) << "decimation " << decimation;
  }
}

// Ids ascending, 4 per tag; left and right points of one id are the images of one corner.
TEST(StereoAprilTagDetector, IdsAscendingAndPairsConsistent)
{
  vpImage<unsigned char> Il, Ir;
  vpSimulatorTagRenderer renderer = renderRandomTags(5, 20, Il, Ir);
  vpStereoAprilTagDetector detector;
  ASSERT_EQ(detector.detect(Il, Ir), 24u);
  const std::vector<int> &ids = detector.getIds();
  ASSERT_EQ(detector.getLeftPoints().size(), ids.size());
  ASSERT_EQ(detector.getRightPoints().size(), ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    EXPECT_EQ(ids[k], 4 * (20 + static_cast<int>(k / 4)) + static_cast<int>(k % 4));
    std::vector<vpImagePoint> left, right;
    renderer.getImageCorners(static_cast<unsigned int>(indexOf(renderer, ids[k] / 4)), left, right);
    EXPECT_LT(vpImagePoint::distance(detector.getLeftPoints()[k], left[k % 4]), 0.3);
    EXPECT_LT(vpImagePoint::distance(detector.getRightPoints()[k], right[k % 4]), 0.3);
  }
}

// The epipolar check: tag 7 is 3 cm lower in the scene the right camera sees than in the left one's (a mismatched
// pair, 50 px off its epipolar lines): its 4 corners are dropped, tag 1's are kept.
TEST(StereoAprilTagDetector, EpipolarCheckDropsAMismatchedPair)
{
  vpSimulatorTagRenderer leftScene(kRig, 1), rightScene(kRig, 2);
  leftScene.addTag(1, 0.04, vpHomogeneousMatrix(-0.05, 0.0, 0.0, 0.2, 0.0, 0.0));
  rightScene.addTag(1, 0.04, vpHomogeneousMatrix(-0.05, 0.0, 0.0, 0.2, 0.0, 0.0));
  leftScene.addTag(7, 0.04, vpHomogeneousMatrix(0.05, 0.0, 0.0, 0.0, 0.3, 0.0));
  rightScene.addTag(7, 0.04, vpHomogeneousMatrix(0.05, 0.03, 0.0, 0.0, 0.3, 0.0));
  vpImage<unsigned char> Il, Ir, unused;
  leftScene.render(Il, unused);
  rightScene.render(unused, Ir);

  vpStereoAprilTagDetector detector;
  EXPECT_EQ(detector.detect(Il, Ir), 8u); // no rig: both tags paired
  vpProjectiveStereoRig rig;
  EXPECT_THROW(detector.setStereoRig(rig), vpProjectiveException); // no F yet
  rig.setFundamentalMatrix(kRig.getFundamentalMatrix());
  detector.setStereoRig(rig);
  ASSERT_EQ(detector.detect(Il, Ir), 4u);
  EXPECT_EQ(detector.getNbEpipolarRejections(), 4u);
  EXPECT_EQ(detector.getIds(), (std::vector<int>{4, 5, 6, 7}));
  detector.clearStereoRig();
  EXPECT_EQ(detector.detect(Il, Ir), 8u);
}

// Tracking: the regions predicted from a full detection give the same corners; a tag predicted elsewhere (it escaped
// its box) is found by the whole-image search, with the same corners; a tag not predicted is not looked for; clearing
// the regions finds it again.
TEST(StereoAprilTagDetector, PredictedRegions)
{
  vpImage<unsigned char> Il, Ir;
  vpSimulatorTagRenderer renderer = renderRandomTags(8, 10, Il, Ir);
  vpStereoAprilTagDetector detector;
  ASSERT_EQ(detector.detect(Il, Ir), 24u);
  const std::vector<int> ids = detector.getIds();
  const std::vector<vpImagePoint> left = detector.getLeftPoints(), right = detector.getRightPoints();

  detector.setPredictedRegions(ids, left, right);
  EXPECT_TRUE(detector.hasPredictedRegions());
  ASSERT_EQ(detector.detect(Il, Ir), 24u);
  EXPECT_EQ(detector.getIds(), ids);
  for (size_t k = 0; k < ids.size(); ++k) {
    EXPECT_LT(vpImagePoint::distance(detector.getLeftPoints()[k], left[k]), 0.02);
    EXPECT_LT(vpImagePoint::distance(detector.getRightPoints()[k], right[k]), 0.02);
  }

  // Tag 10 (the first 4 ids) predicted 150 px away, in both images: found by the whole-image search.
  std::vector<vpImagePoint> movedLeft = left, movedRight = right;
  for (size_t k = 0; k < 4; ++k) {
    movedLeft[k] += vpImagePoint(0.0, 150.0);
    movedRight[k] += vpImagePoint(0.0, 150.0);
  }
  detector.setPredictedRegions(ids, movedLeft, movedRight);
  ASSERT_EQ(detector.detect(Il, Ir), 24u);
  EXPECT_EQ(detector.getIds(), ids);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_LT(vpImagePoint::distance(detector.getLeftPoints()[k], left[k]), 0.02);
  }
  // Tag 10 not predicted at all: not looked for.
  detector.setPredictedRegions(std::vector<int>(ids.begin() + 4, ids.end()),
                               std::vector<vpImagePoint>(left.begin() + 4, left.end()),
                               std::vector<vpImagePoint>(right.begin() + 4, right.end()));
  ASSERT_EQ(detector.detect(Il, Ir), 20u);
  EXPECT_EQ(detector.getIds().front(), 4 * 11);
  detector.clearPredictedRegions();
  EXPECT_EQ(detector.detect(Il, Ir), 24u);
}

// A dark ball in front of one tag hides it in both images; the others are found.
TEST(StereoAprilTagDetector, OccludedTagIsMissing)
{
  vpSimulatorTagRenderer renderer(kRig, 4);
  addRandomTags(renderer, 4, 0);
  const vpHomogeneousMatrix wMt = renderer.getTagPose(0);
  vpColVector centre(3);
  centre[0] = wMt[0][3];
  centre[1] = wMt[1][3];
  centre[2] = wMt[2][3] - 0.1; // 10 cm in front of tag 0
  renderer.setOccluder(centre, 0.03);
  vpImage<unsigned char> Il, Ir;
  renderer.render(Il, Ir);
  vpStereoAprilTagDetector detector;
  ASSERT_EQ(detector.detect(Il, Ir), 20u);
  EXPECT_EQ(detector.getIds().front(), 4);
  renderer.clearOccluder();
  renderer.render(Il, Ir);
  EXPECT_EQ(detector.detect(Il, Ir), 24u);
}

// Tags on three faces of a 6 cm cube carried by a body (a tool), turned so that the three faces face the rig: their 12
// corners (not coplanar) are found in both images, accurately (measured 0.023 and 0.027 px RMS), and follow the body
// when it moves.
TEST(StereoAprilTagDetector, TagsOnAToolCube)
{
  vpSimulatorTagRenderer renderer(kRig, 9);
  const double half = 0.03;
  renderer.addTag(4, 0.035, vpHomogeneousMatrix(0.0, 0.0, -half, 0.0, 0.0, 0.0));       // face -z of the body
  renderer.addTag(5, 0.035, vpHomogeneousMatrix(-half, 0.0, 0.0, 0.0, M_PI / 2, 0.0));  // face -x
  renderer.addTag(6, 0.035, vpHomogeneousMatrix(0.0, -half, 0.0, -M_PI / 2, 0.0, 0.0)); // face -y
  for (int pose = 0; pose < 2; ++pose) {
    const vpHomogeneousMatrix wMb(vpTranslationVector(0.02 * pose, -0.01 * pose, 0.0),
                                  vpRotationMatrix(vpRxyzVector(0.6, -0.6, 0.1 * pose)));
    renderer.setBodyPose(wMb);
    vpImage<unsigned char> Il, Ir;
    renderer.render(Il, Ir);
    vpStereoAprilTagDetector detector;
    ASSERT_EQ(detector.detect(Il, Ir), 12u) << "pose " << pose;
    double sum2 = 0.0, worst = 0.0;
    unsigned int count = 0;
    accumulateErrors(renderer, detector, sum2, count, worst);
    EXPECT_LT(std::sqrt(sum2 / count), 0.06) << "pose " << pose;
    EXPECT_LT(worst, 0.15) << "pose " << pose;
  }
}

// Same seed and settings, same images; another seed, other noise.
TEST(SimulatorTagRenderer, SeededAndReproducible)
{
  vpImage<unsigned char> I[3][2];
  for (int r = 0; r < 3; ++r) {
    vpSimulatorTagRenderer renderer(kRig, r < 2 ? 7 : 8);
    addRandomTags(renderer, 7, 0);
    renderer.render(I[r][0], I[r][1]);
  }
  EXPECT_TRUE(I[0][0] == I[1][0] && I[0][1] == I[1][1]);
  EXPECT_FALSE(I[0][0] == I[2][0]);
}

// A tag seen from behind, or behind the rig, is not drawn; one across the image border is clipped (and not reported
// visible by getImageCorners()).
TEST(SimulatorTagRenderer, HiddenAndClippedTags)
{
  vpSimulatorTagRenderer empty(kRig, 3), hidden(kRig, 3), clipped(kRig, 3);
  hidden.addTag(1, 0.04, vpHomogeneousMatrix(0.0, 0.0, 0.0, 0.0, M_PI, 0.0));  // print facing away from the rig
  hidden.addTag(2, 0.04, vpHomogeneousMatrix(0.0, 0.0, -1.5, 0.0, 0.0, 0.0));  // behind the cameras
  clipped.addTag(3, 0.04, vpHomogeneousMatrix(0.19, 0.0, 0.0, 0.0, 0.0, 0.0)); // across the right border
  vpImage<unsigned char> I[3][2];
  empty.render(I[0][0], I[0][1]);
  hidden.render(I[1][0], I[1][1]);
  clipped.render(I[2][0], I[2][1]);
  EXPECT_TRUE(I[0][0] == I[1][0] && I[0][1] == I[1][1]);
  EXPECT_FALSE(I[0][0] == I[2][0] && I[0][1] == I[2][1]);
  std::vector<vpImagePoint> left, right;
  EXPECT_FALSE(hidden.getImageCorners(0, left, right));
  EXPECT_FALSE(hidden.getImageCorners(1, left, right));
  EXPECT_FALSE(clipped.getImageCorners(0, left, right));
}

TEST(StereoAprilTagDetector, BadInputThrowsAndKeepsTheResults)
{
  vpImage<unsigned char> Il, Ir;
  vpSimulatorTagRenderer renderer = renderRandomTags(6, 0, Il, Ir);
  vpStereoAprilTagDetector detector;
  ASSERT_EQ(detector.detect(Il, Ir), 24u);

  const vpImage<unsigned char> empty, small(240, 320, 128);
  EXPECT_THROW(detector.detect(empty, Ir), vpProjectiveException);
  EXPECT_THROW(detector.detect(Il, empty), vpProjectiveException);
  EXPECT_THROW(detector.detect(Il, small), vpProjectiveException);
  EXPECT_EQ(detector.getIds().size(), 24u); // the previous results are kept

  EXPECT_THROW(detector.setEpipolarThreshold(0.0), vpProjectiveException);
  EXPECT_THROW(detector.setEpipolarThreshold(std::nan("")), vpProjectiveException);
  EXPECT_THROW(detector.setDecimation(0.5), vpProjectiveException);
  EXPECT_THROW(detector.setNbThreads(0), vpProjectiveException);
  EXPECT_THROW(detector.setRegionMargin(-1.0), vpProjectiveException);
  EXPECT_THROW(detector.setPredictedRegions({0, 1}, {vpImagePoint()}, {vpImagePoint()}), vpProjectiveException);
  EXPECT_THROW(detector.setPredictedRegions({-1}, {vpImagePoint()}, {vpImagePoint()}), vpProjectiveException);
  EXPECT_THROW(detector.setPredictedRegions({0}, {vpImagePoint(std::nan(""), 0.0)}, {vpImagePoint()}),
               vpProjectiveException);
  EXPECT_FALSE(detector.hasPredictedRegions());

  EXPECT_THROW(renderer.addTag(32, 0.04, vpHomogeneousMatrix()), vpProjectiveException);
  EXPECT_THROW(renderer.addTag(-1, 0.04, vpHomogeneousMatrix()), vpProjectiveException);
  EXPECT_THROW(renderer.addTag(0, 0.0, vpHomogeneousMatrix()), vpProjectiveException);
  EXPECT_THROW(renderer.setTagPose(6, vpHomogeneousMatrix()), vpProjectiveException);
  vpHomogeneousMatrix infinite;
  infinite[0][3] = std::nan("");
  EXPECT_THROW(renderer.setBodyPose(infinite), vpProjectiveException);
  EXPECT_THROW(renderer.setBlur(-1.0), vpProjectiveException);
  EXPECT_THROW(renderer.setNoise(std::nan("")), vpProjectiveException);
  EXPECT_THROW(renderer.setLighting(-1.0, 0.0), vpProjectiveException);
  EXPECT_THROW(renderer.setOccluder(vpColVector(2, 0.0), 0.01), vpProjectiveException);
  EXPECT_EQ(renderer.getNbTags(), 6u);
}

#else

TEST(StereoAprilTagDetector, NeedsViSPAprilTag)
{
  GTEST_SKIP() << "ViSP was built without AprilTag (VISP_HAVE_APRILTAG)";
}

#endif // VISP_HAVE_APRILTAG
