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
  Identified markers (ids, as AprilTag corners give them) in vpProjectiveArmAcquisition and
  vpProjectiveAcquisitionProcedure: markers matched by id in any order, some hidden in some trial frames, an id the
  zero reference does not have ignored; the model then predicts the true images at the noise level, as with every
  marker in every frame. A marker seen in too few trials is left out of the model and the output says so; too few
  common markers throw with a message that says so. The PUMA-like arm behind vpSimulatorRobotArm, the paper's rig,
  seeded noise.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! The ids of the arm's 7 gripper markers (AprilTag-like: 4 * tag + corner).
const int kIds[7] = {12, 13, 14, 15, 40, 41, 42};
//! A marker the zero reference never shows (it appears only once joint 0 has moved).
const int kStranger = 99;

int armIndexOf(int id)
{
  return static_cast<int>(std::find(kIds, kIds + 7, id) - kIds);
}

struct IdentifiedCell {
  vpSimulatorArm arm;
  vpSimulatorStereoRig sim;
  vpGaussRand noise;
  double sigma;
  vpUniRand shuffle;

  IdentifiedCell()
      : arm(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose())),
        sim(vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0)), noise(1.0, 0.0, 21), sigma(0.5), shuffle(4)
  {
  }

  vpProjectiveStereoRig rig() const
  {
    vpProjectiveStereoRig r;
    r.setFundamentalMatrix(sim.getFundamentalMatrix());
    return r;
  }

  //! The acquisition procedure on \e robot, its cameras giving frame() with the markers \e visible accepts.
  template <typename Visible> vpProjectiveAcquisitionProcedure procedure(vpSimulatorRobotArm &robot, Visible visible)
  {
    return vpProjectiveAcquisitionProcedure(
        [this, &robot, visible](std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                std::vector<vpImagePoint> &right) {
          frame(robot.getArmJoints(), visible, ids, left, right);
          return true;
        },
        sim.getWidth(), sim.getHeight());
  }

  //! An acquisition of the 6R arm with this cell's rig.
  vpProjectiveArmAcquisition acquisition() const
  {
    vpProjectiveArmAcquisition acq(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
    acq.setStereoRig(rig());
    return acq;
  }

  /*!
    Noisy images of the markers at arm joints q whose ids \e visible(id, q) accepts, in a shuffled order; the
    stranger too when joint 0 has moved by more than 3 deg.
  */
  template <typename Visible>
  void frame(const vpColVector &q, Visible visible, std::vector<int> &ids, std::vector<vpImagePoint> &left,
             std::vector<vpImagePoint> &right)
  {
    ids.clear();
    left.clear();
    right.clear();
    const std::vector<vpColVector> X = arm.getMarkers(q);
    for (unsigned int j = 0; j < 7; ++j) {
      vpImagePoint l, r;
      sim.project(X[j], l, r, sigma, noise);
      if (visible(kIds[j], q)) {
        ids.push_back(kIds[j]);
        left.push_back(l);
        right.push_back(r);
      }
    }
    if (std::abs(q[0]) > vpMath::rad(3.0)) {
      vpColVector Y = X[0];
      Y[0] += 0.03; // 3 cm beside marker 12
      vpImagePoint l, r;
      sim.project(Y, l, r, sigma, noise);
      ids.push_back(kStranger);
      left.push_back(l);
      right.push_back(r);
    }
    // Any order: a detector lists what it found as it likes.
    for (size_t k = ids.size(); k > 1; --k) {
      const size_t m = static_cast<size_t>(shuffle.uniform(0, static_cast<int>(k)));
      std::swap(ids[k - 1], ids[m]);
      std::swap(left[k - 1], left[m]);
      std::swap(right[k - 1], right[m]);
    }
  }

  /*!
    RMS error (px) of the model's predictions of the true images at 60 random joints within +-half of \e amounts,
    the model's marker j being the arm's marker of id \e modelIds[j].
  */
  double predictionRms(const vpProjectiveArmModel &model, const std::vector<int> &modelIds, const vpColVector &amounts,
                       const vpColVector &offset) const
  {
    vpUniRand rng(9);
    double sum = 0.0;
    unsigned int count = 0;
    for (int k = 0; k < 60; ++k) {
      vpColVector q(6);
      vpProjectiveArmModel::JointVector qm(6);
      for (unsigned int i = 0; i < 6; ++i) {
        q[i] = rng.uniform(-0.5 * amounts[i], 0.5 * amounts[i]);
        qm[i] = q[i] + offset[i];
      }
      const Eigen::Matrix4d H = model.displacement(qm);
      const std::vector<vpColVector> X = arm.getMarkers(q);
      for (unsigned int j = 0; j < modelIds.size(); ++j) {
        Eigen::Vector4d p;
        vpImagePoint l, r;
        if (model.predictMarker(j, H, p) && sim.project(X[armIndexOf(modelIds[j])], l, r)) {
          sum += (p - Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v())).squaredNorm();
          count += 4;
        }
      }
    }
    EXPECT_GT(count, 4u * 5u * 50u);
    return count == 0 ? 1e9 : std::sqrt(sum / count);
  }
};

const double kTrialDeg[6] = {30.0, 20.0, 30.0, 40.0, 60.0, 60.0};

//! Hidden: marker 13 in the trials of joint 2 positive, 41 in those of joint 4 negative, 15 in joint 0's.
bool partlyHidden(int id, const vpColVector &q)
{
  return !((id == 13 && q[2] > vpMath::rad(5.0)) || (id == 41 && q[4] < vpMath::rad(-5.0)) ||
           (id == 15 && std::abs(q[0]) > vpMath::rad(5.0)));
}

bool allVisible(int, const vpColVector &)
{
  return true;
}

template <typename Visible>
vpProjectiveArmModel calibrateByHand(IdentifiedCell &cell, Visible visible, vpProjectiveArmAcquisition &acq)
{
  acq = cell.acquisition();
  std::vector<int> ids;
  std::vector<vpImagePoint> left, right;
  cell.frame(vpColVector(6, 0.0), visible, ids, left, right);
  acq.setZeroReference(vpColVector(6, 0.0), ids, left, right);
  for (unsigned int i = 0; i < 6; ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      vpColVector q(6, 0.0);
      q[i] = sign * vpMath::rad(kTrialDeg[i]) * (i == 1 && sign < 0 ? 0.9 : 1.0);
      cell.frame(q, visible, ids, left, right);
      acq.addTrialMotion(q, ids, left, right);
    }
  }
  return acq.calibrate();
}
} // namespace

TEST(AcquisitionIdentifiedMarkers, HiddenAndShuffledMarkersCalibrateAtTheNoiseLevel)
{
  vpColVector amounts(6);
  for (unsigned int i = 0; i < 6; ++i) {
    amounts[i] = vpMath::rad(kTrialDeg[i]) * (i == 1 ? 0.9 : 1.0);
  }
  IdentifiedCell cell;
  vpProjectiveArmAcquisition all;
  const vpProjectiveArmModel modelAll = calibrateByHand(cell, allVisible, all);
  IdentifiedCell cellHidden;
  vpProjectiveArmAcquisition acq;
  const vpProjectiveArmModel model = calibrateByHand(cellHidden, partlyHidden, acq);

  ASSERT_EQ(acq.getMarkerIds(), std::vector<int>(kIds, kIds + 7)); // ascending, the stranger ignored
  ASSERT_EQ(acq.getNumberOfTrials(), 12u);
  unsigned int missing = 0;
  for (unsigned int k = 0; k < 12; ++k) {
    for (unsigned int j = 0; j < 7; ++j) {
      missing += acq.isObserved(k, j) ? 0u : 1u;
      EXPECT_FALSE(acq.isOutlier(k, j));
    }
  }
  EXPECT_EQ(missing, 4u);             // 13 once, 41 once, 15 twice
  EXPECT_FALSE(acq.isObserved(5, 1)); // trial 5, joint 2 positive: marker 13
  EXPECT_EQ(acq.getNumberOfOutliers(), 0u);
  EXPECT_LT(acq.getCalibrationResidual(), 1.5 * cell.sigma);
  const double eAll = cell.predictionRms(modelAll, all.getMarkerIds(), amounts, vpColVector(6, 0.0));
  const double eHidden = cellHidden.predictionRms(model, acq.getMarkerIds(), amounts, vpColVector(6, 0.0));
  EXPECT_LT(eHidden, cell.sigma);
  EXPECT_LT(eHidden, 1.5 * eAll);
  RecordProperty("prediction_all_px", std::to_string(eAll));
  RecordProperty("prediction_hidden_px", std::to_string(eHidden));

  // The same with outlier rejection on: the missing markers are not outliers.
  acq.setOutlierThreshold(3.0 * cell.sigma);
  const vpProjectiveArmModel robust = acq.calibrate();
  EXPECT_EQ(acq.getNumberOfOutliers(), 0u);
  EXPECT_LT(cellHidden.predictionRms(robust, acq.getMarkerIds(), amounts, vpColVector(6, 0.0)), cell.sigma);
}

TEST(AcquisitionIdentifiedMarkers, TooFewCommonMarkersOrRepeatedIdsThrow)
{
  IdentifiedCell cell;
  vpProjectiveArmAcquisition acq = cell.acquisition();
  std::vector<int> ids;
  std::vector<vpImagePoint> left, right;
  cell.frame(vpColVector(6, 0.0), allVisible, ids, left, right);
  std::vector<int> twice = ids;
  twice[1] = twice[0];
  EXPECT_THROW(acq.setZeroReference(vpColVector(6, 0.0), twice, left, right), vpProjectiveException);
  EXPECT_THROW(acq.setZeroReference(vpColVector(6, 0.0), std::vector<int>(6, 1), left, right), vpProjectiveException);
  acq.setZeroReference(vpColVector(6, 0.0), ids, left, right);
  vpColVector q(6, 0.0);
  q[3] = vpMath::rad(20.0);
  cell.frame(
      q, [](int id, const vpColVector &) { return id == 12 || id == 13 || id == 40 || id == 41; }, ids, left, right);
  try {
    acq.addTrialMotion(q, ids, left, right);
    FAIL() << "no exception";
  } catch (const vpProjectiveException &e) {
    EXPECT_EQ(e.getCode(), vpProjectiveException::notEnoughPointsError);
    EXPECT_NE(e.getStringMessage().find("4 of the zero reference's 7"), std::string::npos) << e.getStringMessage();
  }
  EXPECT_EQ(acq.getNumberOfTrials(), 0u); // unchanged
}

/*
  The procedure with an identified source on vpSimulatorRobotArm (encoder offset): markers hidden in some trial
  frames and shuffled, a stranger never seen at the zero reference: the model predicts at the noise level, as the
  one acquired with every marker in every frame.
*/
TEST(AcquisitionIdentifiedMarkers, ProcedureToleratesMissingMarkers)
{
  const vpColVector offset({0.1, 0.2, -0.3, 0.4, 0.5, -0.6});
  vpColVector amounts;
  double errors[2] = {0.0, 0.0};
  for (int hidden = 0; hidden < 2; ++hidden) {
    IdentifiedCell cell;
    vpSimulatorRobotArm robot(cell.arm);
    robot.setEncoderOffset(offset);
    vpProjectiveAcquisitionProcedure procedure(
        [&](std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
          const vpColVector q = robot.getArmJoints();
          if (hidden) {
            cell.frame(q, partlyHidden, ids, left, right);
          } else {
            cell.frame(q, allVisible, ids, left, right);
          }
          return true;
        },
        cell.sim.getWidth(), cell.sim.getHeight());
    procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
    procedure.setMaxAmounts(vpColVector(6, vpMath::rad(20.0)));
    std::ostringstream log;
    procedure.setOutput(&log);
    vpProjectiveArmAcquisition acq = cell.acquisition();
    const vpProjectiveArmModel model = procedure.run(robot, acq);
    EXPECT_EQ(acq.getMarkerIds(), std::vector<int>(kIds, kIds + 7));
    EXPECT_TRUE(procedure.getDroppedMarkers().empty());
    EXPECT_EQ(acq.getNumberOfTrials(), 12u);
    EXPECT_LT(procedure.getCalibrationResidual(), 1.5 * cell.sigma);
    EXPECT_TRUE(procedure.getMountingReport().checked);
    amounts.resize(6);
    for (unsigned int i = 0; i < 6; ++i) {
      const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[i];
      amounts[i] = std::min(r.amountNegative, r.amountPositive);
    }
    errors[hidden] = cell.predictionRms(model, acq.getMarkerIds(), amounts, offset);
    EXPECT_LT(errors[hidden], cell.sigma);
    if (hidden) {
      unsigned int missing = 0;
      for (unsigned int k = 0; k < acq.getNumberOfTrials(); ++k) {
        for (unsigned int j = 0; j < 7; ++j) {
          missing += acq.isObserved(k, j) ? 0u : 1u;
        }
      }
      EXPECT_GE(missing, 3u);
    }
  }
  EXPECT_LT(errors[1], 1.5 * errors[0]);
  RecordProperty("prediction_all_px", std::to_string(errors[0]));
  RecordProperty("prediction_hidden_px", std::to_string(errors[1]));
}

/*
  A marker hidden as soon as any joint moves is seen in no trial: it is left out of the model, and the output says
  so; three markers hidden that way leave 4 common markers: the run throws, saying why.
*/
TEST(AcquisitionIdentifiedMarkers, RarelySeenMarkerDroppedTooFewCommonMarkersThrow)
{
  auto movedAtAll = [](const vpColVector &q) { return q.frobeniusNorm() > vpMath::rad(1.0); };
  {
    IdentifiedCell cell;
    vpSimulatorRobotArm robot(cell.arm);
    vpProjectiveAcquisitionProcedure procedure =
        cell.procedure(robot, [&](int id, const vpColVector &qq) { return id != 42 || !movedAtAll(qq); });
    procedure.setMaxAmounts(vpColVector(6, vpMath::rad(20.0)));
    std::ostringstream log;
    procedure.setOutput(&log);
    vpProjectiveArmAcquisition acq = cell.acquisition();
    const vpProjectiveArmModel model = procedure.run(robot, acq);
    EXPECT_EQ(procedure.getDroppedMarkers(), std::vector<int>(1, 42));
    EXPECT_EQ(acq.getMarkerIds(), std::vector<int>(kIds, kIds + 6));
    EXPECT_EQ(model.markers().size(), 6u);
    EXPECT_NE(log.str().find("marker 42 left out: seen in 0 of 12"), std::string::npos) << log.str();
    vpColVector amounts(6);
    for (unsigned int i = 0; i < 6; ++i) {
      amounts[i] = std::min(procedure.getReports()[i].amountNegative, procedure.getReports()[i].amountPositive);
    }
    EXPECT_LT(cell.predictionRms(model, acq.getMarkerIds(), amounts, vpColVector(6, 0.0)), cell.sigma);
  }
  {
    IdentifiedCell cell;
    vpSimulatorRobotArm robot(cell.arm);
    vpProjectiveAcquisitionProcedure procedure =
        cell.procedure(robot, [&](int id, const vpColVector &qq) { return id < 40 || !movedAtAll(qq); });
    vpProjectiveArmAcquisition acq = cell.acquisition();
    try {
      procedure.run(robot, acq);
      FAIL() << "no exception";
    } catch (const vpProjectiveException &e) {
      EXPECT_NE(e.getStringMessage().find("too few common markers"), std::string::npos) << e.getStringMessage();
    }
    EXPECT_EQ(acq.getNumberOfTrials(), 0u);
    EXPECT_LT(robot.getArmJoints().frobeniusNorm(), 1e-4); // back at the zero reference
  }
}

/*
  Without a rig: the procedure estimates it from the identified markers' pairs it saw, and the model from pixels and
  encoder readings predicts at the noise level with markers missing from some trial frames; bad settings throw.
*/
TEST(AcquisitionIdentifiedMarkers, EstimatesTheRigFromIdentifiedMarkers)
{
  IdentifiedCell cell;
  vpSimulatorRobotArm robot(cell.arm);
  vpProjectiveAcquisitionProcedure procedure = cell.procedure(robot, partlyHidden);
  EXPECT_THROW(procedure.setMinMarkerVisibility(1.5), vpProjectiveException);
  EXPECT_THROW(procedure.setMinMarkerVisibility(std::nan("")), vpProjectiveException);
  procedure.setMaxAmounts(vpColVector(6, vpMath::rad(20.0)));
  vpProjectiveArmAcquisition acq(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
  const vpProjectiveArmModel model = procedure.run(robot, acq);
  ASSERT_TRUE(acq.getStereoRig().isInitialized());
  EXPECT_EQ(acq.getMarkerIds(), std::vector<int>(kIds, kIds + 7));
  EXPECT_LT(procedure.getCalibrationResidual(), 1.5 * cell.sigma);
  vpColVector amounts(6);
  for (unsigned int i = 0; i < 6; ++i) {
    amounts[i] = std::min(procedure.getReports()[i].amountNegative, procedure.getReports()[i].amountPositive);
  }
  const double e = cell.predictionRms(model, acq.getMarkerIds(), amounts, vpColVector(6, 0.0));
  EXPECT_LT(e, cell.sigma);
  RecordProperty("prediction_px", std::to_string(e));
}
