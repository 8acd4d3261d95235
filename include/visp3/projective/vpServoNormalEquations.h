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

/*!
  \file vpServoNormalEquations.h
  \brief The normal equations of a servo task and their factorisations, each computed at most once per iteration and
  read by every part of the control law.
*/

#ifndef _vpServoNormalEquations_h_
#define _vpServoNormalEquations_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoNormalEquations
  \ingroup group_projective
  \brief The normal equations \f$ J^T J \f$ (n x n) and \f$ J^T e \f$ (n x 1) of a task (\f$ J \f$ m x n, task units
  per joint unit; \f$ e \f$ m x 1, task units) and their factorisations, each computed at most once, at its first use:
  the one place where the control law's parts solve or decompose \f$ J^T J \f$.

  - the Cholesky factorisation \f$ L L^T = J^T J \f$ and the Gauss-Newton step
    \f$ g = (J^T J)^{-1} J^T e \f$ (getGaussNewtonStep()): the undamped law (\f$ \dot q = -\lambda g \f$,
    vpServoDampedLeastSquares away from singularities), the adaptive gain on \f$ J^+ e \f$
    (vpServoControlLaw::GAIN_INPUT_JOINT_VELOCITY) and the settling test (vpServoSettling) read the same \f$ g \f$;
    where \f$ J^T J \f$ is not numerically positive definite, \f$ g \f$ is Eigen's pivoting LDLT solution, what it
    gives of a singular system;
  - \f$ \mathrm{tr}((J^T J)^{-1}) = \|L^{-1}\|_F^2 = \sum_k 1 / \sigma_k^2 \ge 1 / \sigma_{min}^2 \f$
    (getInverseTrace()): below \f$ 1 / \sigma_0^2 \f$ it proves \f$ \sigma_{min} > \sigma_0 \f$, which spares the
    damped law the eigenvalues away from singularities;
  - the eigen decomposition \f$ J^T J = V \Lambda V^T \f$ (getEigenvalues(), getEigenvectors()): the damping near
    singularities and its solve (solveDamped()), the null-space projector of the joint-limit avoidance
    (vpServoDampedLeastSquares::addNullSpaceProjector()), the condition number of vpServoProjectiveReport.

  A servo iteration fills one object (vpServoProjectiveData::getNormalEquations()) and hands it to each part: the
  Cholesky factorisation is computed once per iteration and the eigen decomposition at most once, only near a
  singularity or when the joint-limit avoidance needs its projector. getFactorisationCount() counts them since the
  last compute() or set(), so that a test can check it.

  Fixed-size storage (at most vpProjectiveArmModel::maxJoints joints): no allocation. Not thread-safe for concurrent
  readers: the factorisations are computed inside the const getters.
*/
class VISP_EXPORT vpServoNormalEquations
{
public:
  typedef vpProjectiveArmModel::JointVector JointVector; //!< n x 1, no heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix; //!< n x n, no heap allocation.

  //! Empty normal equations (n = 0).
  vpServoNormalEquations();

  /*! \name The equations */
  //@{
  /*!
    \f$ J^T J \f$ and \f$ J^T e \f$ of \e J (m x n, \f$ n \le \f$ maxJoints) and \e e (m x 1), by column dot products
    with the lower triangle mirrored (exactly symmetric); forgets the factorisations. Sizes not checked.
  */
  void compute(const Eigen::MatrixXd &J, const Eigen::VectorXd &e);
  /*!
    Given normal equations: \e JtJ (n x n, symmetric) and \e Jte (n x 1), for instance a task with some joints held
    (vpServoControlLaw::keepInside()); forgets the factorisations. Sizes not checked.
  */
  void set(const JointMatrix &JtJ, const JointVector &Jte);
  //! \f$ J^T J \f$ (n x n).
  const JointMatrix &getJtJ() const { return m_JtJ; }
  //! \f$ J^T e \f$ (n x 1).
  const JointVector &getJte() const { return m_Jte; }
  //! The number of joints n.
  Eigen::Index size() const { return m_JtJ.rows(); }
  //@}

  /*! \name Factorisations (each computed at its first use after compute() or set()) */
  //@{
  //! True if the Cholesky factorisation of \f$ J^T J \f$ succeeded (every pivot positive and finite).
  bool isPositiveDefinite() const;
  /*!
    \f$ g = (J^T J)^{-1} J^T e \f$ (n x 1): by the Cholesky factor where isPositiveDefinite(), by Eigen's pivoting LDLT
    otherwise (then possibly not finite: callers check).
  */
  const JointVector &getGaussNewtonStep() const;
  //! \f$ \mathrm{tr}((J^T J)^{-1}) = \|L^{-1}\|_F^2 \ge 1 / \sigma_{min}^2 \f$; infinite if not isPositiveDefinite().
  double getInverseTrace() const;
  //! The eigenvalues of \f$ J^T J \f$ (n x 1, ascending: \f$ \sigma_k^2 \f$, possibly slightly negative by rounding).
  const JointVector &getEigenvalues() const;
  //! The eigenvectors of \f$ J^T J \f$ (n x n, orthonormal columns in the order of getEigenvalues()).
  const JointMatrix &getEigenvectors() const;
  /*!
    \e x \f$ = (J^T J + \mu^2 I_n)^{-1} J^T e \f$ (n x 1, resized) for \f$ \mu^2 > 0 \f$, through the eigen
    decomposition: \f$ V (\Lambda + \mu^2 I)^{-1} V^T J^T e \f$, each eigenvalue clamped at 0 first.
  */
  void solveDamped(double mu2, JointVector &x) const;
  //! The factorisations computed since the last compute() or set(): Cholesky, LDLT and eigen decompositions.
  unsigned int getFactorisationCount() const { return m_factorisations; }
  //@}

private:
  void factoriseCholesky() const;
  void solveGaussNewton() const;
  void decompose() const;

  JointMatrix m_JtJ;
  JointVector m_Jte;
  // The factorisations, computed inside the const getters at their first use.
  mutable JointMatrix m_L; // the Cholesky factor: its strictly lower triangle, the reciprocals of its diagonal
  mutable JointVector m_g;
  mutable double m_inverseTrace;
  mutable JointVector m_eigenvalues;
  mutable JointMatrix m_eigenvectors;
  mutable bool m_hasCholesky, m_positiveDefinite, m_hasStep, m_hasInverseTrace, m_hasEigen;
  mutable unsigned int m_factorisations;
};

END_VISP_NAMESPACE

#endif
