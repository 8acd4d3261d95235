/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*
 * libFuzzer target on the model loader vpProjectiveModelFile::fromString(), the parser behind
 * vpProjectiveRobot::loadModel() (tests/fuzz/run-fuzz.sh builds and runs it).
 *
 * The first input byte selects the mode and is not part of the file:
 *  - odd  (the seeds use 'c'): if the rest parses as a JSON object with a "model" member, the harness re-signs it
 *    (the checksum recomputed independently of the library, tests/vpModelFileChecksum.h), so that the mutations reach
 *    the entries' checks behind the checksum;
 *  - even (the seeds use 'r'): the rest is read as is (JSON syntax, checksum validation, truncation, raw garbage).
 * Any vpException is an expected outcome (the loader rejected the file); a crash, a sanitizer report, or any other
 * exception escaping the loader is a finding. A model that loads is used once (forward kinematics, a generator).
 */
#include <cstdint>
#include <string>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveArmData.h>
#include <visp3/projective/vpProjectiveModelFile.h>

#include "../vpModelFileChecksum.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (size == 0) {
    return 0;
  }
  std::string text(reinterpret_cast<const char *>(data + 1), size - 1);
  if (data[0] & 1) {
    const nlohmann::json file = nlohmann::json::parse(text, nullptr, false); // no exception: discarded on error
    if (!file.is_discarded() && file.is_object() && file.contains("model")) {
      text = vpProjectiveTest::resigned(file);
    }
  }
  vpProjectiveArmModel model;
  try {
    model = vpProjectiveModelFile::fromString(text, "fuzz input");
  } catch (const vpException &) {
    return 0; // rejected: the expected outcome for almost every input
  }
  // A model that loads must be usable: forward kinematics at two configurations and a joint's motion.
  const unsigned int n = model.getNumberOfJoints();
  Eigen::Matrix4d H = model.displacement(vpProjectiveArmModel::JointVector::Zero(n));
  H = model.displacement(vpProjectiveArmModel::JointVector::Constant(n, 0.1));
  vpProjectiveArmData arm;
  vpProjectiveKinematics::forwardKinematics(model, arm, vpProjectiveArmModel::JointVector::Constant(n, 0.2));
  vpProjectiveArmModel::PointJacobian J;
  vpProjectiveKinematics::imageJacobian(model, arm, H * model.markers()[0], J);
  return 0;
}
