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
  \file vpSimulatorStereoCell.h
  \brief A rendered robot cell: a simulated arm behind vpRobot, printed AprilTags on its tool or in the scene, and
  the two images of a stereo rig, as a vpStereoImageSource.
*/

#ifndef _vpSimulatorStereoCell_h_
#define _vpSimulatorStereoCell_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpSimulatorTagRenderer.h>
#include <visp3/projective/vpStereoImageSource.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorStereoCell
  \ingroup group_projective_simulator
  \brief A robot cell as a program sees real hardware: the arm is a vpRobot (vpSimulatorRobotArm: joint velocity and
  position control, both sampling modes, encoder readings), the two cameras are a vpStereoImageSource whose
  acquire() renders, at the arm's current joints, the printed AprilTags of the cell (vpSimulatorTagRenderer:
  perspective, anti-aliasing, blur, noise, lighting, occluder).

  Frames: \c w the world (the rig's, vpSimulatorStereoRig), \c t the arm's tool (vpSimulatorArm::get_wMt()), \c g a
  tag's own frame (vpSimulatorTagRenderer: centre of the black square, \f$ z \f$ into the tag). A tool tag is fixed
  in the tool frame (\f$ {}^tM_g \f$, addToolTag()); a scene tag in the world (\f$ {}^wM_g \f$, addSceneTag()).

  Mounting: eye-to-hand (default) keeps the rig fixed in the world. Eye-in-hand (setEyeInHand()) fixes the rig on
  the arm's last link, \f$ {}^wM_l(q) = {}^wM_e(q)\, {}^eM_l \f$ with \f$ {}^eM_l \f$ the relation at the joints
  where setEyeInHand() is called (the rig given to the constructor is where the cameras are at those joints).

  \code
  vpSimulatorStereoCell cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
                             vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0));
  cell.addToolTags(0.03);                        // three 3 cm tags (ids 0, 1, 2) on the gripper's front
  vpRobot &robot = cell.getRobot();              // velocity or position control, as a real arm
  vpImage<unsigned char> Ileft, Iright;
  cell.acquire(Ileft, Iright);                   // what the cameras see now
  \endcode
*/
class VISP_EXPORT vpSimulatorStereoCell : public vpStereoImageSource
{
public:
  /*!
    A cell of \e arm (at joints \e q0: n x 1, default zero; vpSimulatorRobotArm) seen by \e rig; \e seed seeds the
    images' noise.
  */
  vpSimulatorStereoCell(const vpSimulatorArm &arm, const vpSimulatorStereoRig &rig,
                        const vpColVector &q0 = vpColVector(), long seed = 1);

  /*!
    Prints tag \e id (36h11, 0 to 31; the side \e size of its black square in metres) on the tool at \f$ {}^tM_g \f$.
    Returns its index in getRenderer().
    \exception vpProjectiveException as vpSimulatorTagRenderer::addTag().
  */
  unsigned int addToolTag(int id, double size, const vpHomogeneousMatrix &tMg);
  /*!
    Three tags (ids \e firstId to \e firstId + 2) of side \e size on a holder in front of the gripper of
    vpSimulatorArm::gripperMarkers(), whose face \f$ y_t < 0 \f$ looks at the rig at the zero reference: the middle
    one faces \f$ -y_t \f$, the outer two are turned by 55 deg about \f$ z_t \f$ to either side, so that their 12
    corners are on three planes (an acquisition needs markers off one plane) and all face the rig.
  */
  void addToolTags(double size, int firstId = 0);
  /*!
    Prints tag \e id fixed in the world at \f$ {}^wM_g \f$ (a scene for an eye-in-hand rig). Returns its index.
  */
  unsigned int addSceneTag(int id, double size, const vpHomogeneousMatrix &wMg);
  /*!
    Fixes the rig on the arm's last link from now on: the rig's pose relative to the last link is the one at the
    arm's current joints (see the class description).
  */
  void setEyeInHand();
  //! Whether the rig rides on the last link (setEyeInHand()).
  bool isEyeInHand() const { return m_eyeInHand; }

  //! The arm, as a vpRobot: what a program servoes.
  vpSimulatorRobotArm &getRobot() { return m_robot; }
  //! The renderer: setNoise(), setBlur(), setLighting(), setOccluder(), ...
  vpSimulatorTagRenderer &getRenderer() { return m_renderer; }
  //! The rig at the joints of the last acquire() (eye-to-hand: the one given to the constructor).
  const vpSimulatorStereoRig &getStereoRig() const { return m_rig; }

  /*!
    The cameras' timing, as a real cell has it. Default (\e frameRate 0): every acquire() renders the arm as it is
    now. With \e frameRate > 0 (Hz), frame k is taken at \f$ k / \f$ \e frameRate seconds of the robot's simulated
    time (vpSimulatorRobotArm::getTime()) by the left camera and \e skew seconds later (negative: earlier) by the
    right one, and delivered \e latency (>= 0) seconds after the later of the two; it is lost with the probability
    \e dropRate (0 to 0.9; each frame's fate drawn from \e seed and its number, whatever the calls). acquire() then
    gives the newest frame delivered by now that it did not give yet (older ones are skipped, as a grabber that keeps
    the latest frame does) and, when there is none, lets the time pass until the next one arrives
    (vpSimulatorRobotArm::wait(): the arm moves on at its command, as a real one does while the program waits for a
    camera); each image shows the arm when it was taken (vpSimulatorRobotArm::getArmJointsAt()), and getTimestamps()
    tells those instants.
    \exception vpProjectiveException (invalidValueError) on a negative or non-finite rate or latency, a non-finite
    skew, or a drop rate outside [0, 0.9]; nothing changes then.
  */
  void setTiming(double frameRate, double latency = 0.0, double skew = 0.0, double dropRate = 0.0, long seed = 1);

  /*!
    Renders the two images of the next frame: the arm at its current joints (vpSimulatorRobotArm::getArmJoints()),
    or, with setTiming(), at the instants the images were taken. Always true: a rendered cell never runs out of
    images.
  */
  bool acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) override;
  /*!
    The instants (robot's simulated time, seconds) the images of the last acquire() show: the robot's time at the
    call without setTiming(). False before the first acquire().
  */
  bool getTimestamps(double &left, double &right) const override;
  //! Image width (pixels).
  unsigned int getWidth() const override { return m_rig.getWidth(); }
  //! Image height (pixels).
  unsigned int getHeight() const override { return m_rig.getHeight(); }

  /*!
    The true image positions, at the arm's current joints, of every tag corner visible in both images: \e ids as
    vpStereoAprilTagDetector gives them (4 * tag id + corner index, ascending), \e left and \e right in their
    order. Returns their number.
  */
  unsigned int getTrueCorners(std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right);

private:
  struct ToolTag {
    unsigned int index;      // in the renderer
    vpHomogeneousMatrix tMg; // tool frame to tag
  };
  void update(const vpColVector &q);
  bool dropped(long frame) const;

  vpSimulatorRobotArm m_robot;
  vpSimulatorStereoRig m_rig0; // the rig at the joints of setEyeInHand() (or the fixed one)
  vpSimulatorTagRenderer m_renderer;
  vpSimulatorStereoRig m_rig;
  std::vector<ToolTag> m_toolTags;
  std::vector<vpHomogeneousMatrix> m_sceneTags; // wMg of the scene tags, by renderer index (identity for tool tags)
  bool m_eyeInHand;
  vpHomogeneousMatrix m_eMw0;                        // eye-in-hand: last link to world at setEyeInHand()
  double m_frameRate, m_latency, m_skew, m_dropRate; // setTiming()
  long m_timingSeed;
  long m_lastFrame;                 // the number of the last frame acquire() gave (setTiming())
  double m_stampLeft, m_stampRight; // when the images of the last acquire() were taken (NaN: none yet)
  vpImage<unsigned char> m_scratch; // the image rendered at the other camera's instant, when they differ
};

END_VISP_NAMESPACE

#endif
