/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*!
  \file vpServoProjective.h
  \brief Non-metric joint-space visual servoing from an uncalibrated stereo rig.
*/

#ifndef _vpServoProjective_h_
#define _vpServoProjective_h_

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/vs/vpAdaptiveGain.h>

/*!
  \class vpServoProjective
  \ingroup group_projective
  \brief The non-metric visual servo of Ruf & Horaud (section 6): joint velocities from the image error of stereo
  point features, through the projective kinematic model of the arm. No intrinsics, rig geometry, robot geometry or
  hand-eye transform enter it.

  For \f$ N \f$ stereo points the task error is \f$ e = s - s^* \f$ (4N), and the task Jacobian \f$ J \f$ (4N x n)
  stacks, for each point, eq. (46) at the current joint values \f$ q \f$ and the point \f$ M \f$ triangulated from the
  current features:
  \f[ J_i = \begin{bmatrix} J_C(P M_i) P \\ J_C(P' M_i) P' \end{bmatrix} J_H(q, M_i). \f]
  The control law (47) is \f$ \dot q = -\lambda J^+ e \f$, with the pseudo-inverse damped near singular
  configurations: \f$ J^+ = (J^T J + \mu^2 I)^{-1} J^T \f$, \f$ \mu^2 = \mu_{max}^2 (1 - (\sigma_{min} /
  \sigma_0)^2) \f$ when the smallest singular value \f$ \sigma_{min} \f$ of J falls below \f$ \sigma_0 \f$, 0 otherwise.

  Like vpServo, the task keeps references to the features: the loop updates them and calls computeControlLaw().
  \code
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  for (unsigned int i = 0; i < 3; ++i)
    task.addFeature(s[i], s_star[i]);
  while (!converged) {
    // ... track the points, then s[i].buildFrom(ipLeft[i], ipRight[i]);
    vpColVector qdot = task.computeControlLaw(q);
    // send qdot to the robot
  }
  \endcode
*/
class VISP_EXPORT vpServoProjective
{
public:
  vpServoProjective();

  /*!
    The acquired projective model of the arm (calibrated or loaded). The task keeps a reference: the robot must
    outlive it.
  */
  void setRobot(const vpProjectiveRobot &robot);
  //! Constant gain \f$ \lambda > 0 \f$.
  void setLambda(double lambda);
  //! Adaptive gain, a function of the infinity norm of the error (see vpAdaptiveGain).
  void setLambda(const vpAdaptiveGain &lambda);
  //! Adaptive gain from its value at zero error, at infinite error and its slope at zero.
  void setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero);
  /*!
    Damped least squares: below \e sigmaThreshold (pixels per joint unit) for the smallest singular value of J, the
    damping \f$ \mu \f$ rises to \e maxDamping. Defaults: 1 and 10. Three markers 8 cm apart seen from 1 m give
    \f$ \sigma_{min} \f$ of 1 to 50 pixels per radian in healthy poses: a higher threshold keeps damping on near the
    target, which does not move the fixed point (\f$ J^T e = 0 \f$) but slows the final convergence. For large
    initial errors, combine a higher threshold with setMaxJointVelocity().
  */
  void setDamping(double sigmaThreshold, double maxDamping);
  /*!
    Velocity saturation: when some \f$ |\dot q_i| \f$ exceeds \e qdotMax (joint units per call), the whole
    \f$ \dot q \f$ is scaled down so that the largest one equals it, which keeps its direction. Large initial errors
    otherwise ask for joint steps far beyond the validity of the linearisation. 0 (the default) disables it.
  */
  void setMaxJointVelocity(double qdotMax);

  /*!
    Adds a stereo point and its desired value. Both are kept by reference, like vpServo::addFeature().
  */
  void addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star);
  //! Removes every feature.
  void clearFeatures();
  //! Number of stereo point features \f$ N \f$ added.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_features.size()); }

  /*!
    \f$ \dot q = -\lambda J^+ (s - s^*) \f$ at joint values \e q.
    \exception vpProjectiveException if the robot or the features are missing, q has the wrong size or is not
    finite, there are fewer equations than joints, or a feature cannot be triangulated.
  */
  vpColVector computeControlLaw(const vpColVector &q);
  //! The same on Eigen types, without allocation once the sizes are known.
  void computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot);

  //! \f$ e = s - s^* \f$ (4N) of the last computeControlLaw().
  vpColVector getError() const;
  //! \f$ J \f$ (4N x n) of the last computeControlLaw().
  vpMatrix getTaskJacobian() const;
  /*!
    Condition number \f$ \sigma_{max} / \sigma_{min} \f$ of \f$ J \f$ at the last computeControlLaw() (infinite if
    \f$ J \f$ is rank deficient). Computed on the first call after computeControlLaw() from the \f$ J^T J \f$ it
    kept, so that the control loop does not pay for an eigen-decomposition it needs only near singularities.
  */
  double getConditionNumber() const;
  //! Damping \f$ \mu \f$ used at the last computeControlLaw() (0 away from singularities).
  double getDamping() const { return m_damping; }
  //! Gain used at the last computeControlLaw().
  double getLambda() const { return m_lambdaUsed; }
  //! True if the last computeControlLaw() was scaled down by the velocity saturation.
  bool isSaturated() const { return m_saturated; }

private:
  //! Square matrices of joint size, in fixed storage (no allocation).
  typedef Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, vpProjectiveRobot::maxJoints,
                        vpProjectiveRobot::maxJoints>
      JointMatrix;

  void check(const char *method) const;
  void computeSpectrum() const;

  const vpProjectiveRobot *m_robot;
  std::vector<vpFeatureStereoPoint *> m_features;
  std::vector<vpFeatureStereoPoint *> m_desired;
  vpAdaptiveGain m_lambda;
  double m_sigmaThreshold;
  double m_maxDamping;
  double m_qdotMax;
  Eigen::MatrixXd m_J;
  Eigen::VectorXd m_e;
  JointMatrix m_JtJ;            // J^T J of the last computeControlLaw(), for getConditionNumber()
  mutable bool m_spectrumValid; // m_sigmaMin and m_condition are those of m_JtJ
  mutable double m_sigmaMin;
  mutable double m_condition;
  double m_damping;
  double m_lambdaUsed;
  bool m_saturated;
};

#endif
