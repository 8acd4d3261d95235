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
  \file vpStereoDotTracker.h
  \brief Markers tracked in both images of a stereo rig by ViSP's vpDot2, with their left-right correspondences kept
  by the epipolar geometry and, when there is one, by the projective model of the arm that carries them.
*/

#ifndef _vpStereoDotTracker_h_
#define _vpStereoDotTracker_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/blob/vpDot2.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpStereoDotTracker
  \ingroup group_projective
  \brief Blob markers (lit balls, retro-reflective discs) tracked frame by frame in the left and right images of a
  stereo rig: the image measurements that vpFeatureStereoPoint, vpProjectiveRobot's acquisition and inverse kinematics
  consume.

  Each marker is a pair of vpDot2 trackers, one per image; marker \e k keeps its identity from its initialisation on.
  - Initialisation: from image points near the markers (initTracking(), e.g. a program's own detection), from a
    user's clicks (initTrackingByClick(), vpDisplay::getClick() in each image), or by automatic blob detection when the
    number of markers is known (initTrackingByDetection()): the bright blobs of both images are paired by the
    epipolar geometry (setStereoRig()), or assigned to the markers that the projective model predicts (setRobot()).
  - Prediction: each frame, every blob is first predicted, from the model's predicted marker images at the joint
    values given to track() when there is a model, otherwise at constant image velocity (scaled by the ratio of this
    frame's motion to the last one's). vpDot2::track() then looks for it from there.
  - Checks, on the blobs alone: a blob predicted or found within getMinimumGap() pixels (edge to edge) of another one
    is about to merge with it; a blob at the image border is leaving the image; an area that jumps is a blob merged
    with or hidden by another one; a blob found farther than its radius plus half the gap from its prediction is
    another blob that vpDot2 jumped to; a pair farther than getEpipolarThreshold() from its epipolar line is not a
    correspondence. Such a marker is MARKER_LOST for this frame: its position is then its prediction, never a wrong
    measurement.
  - Recovery: a lost blob is searched for near its predicted position every frame (brightest pixel within
    getSearchRadius(), then vpDot2 with the grey levels of its first detection, and the same checks); found again in
    both images, the marker is MARKER_REDETECTED, then MARKER_TRACKED. Two blobs that cross each other are therefore
    lost while they overlap and found again, each with its own identity, once they are apart.

  A copy of the tracker is an independent tracker (the robot given to setRobot() is shared: it must outlive the
  tracker and its copies).

  \code
  vpStereoDotTracker tracker;
  tracker.initTrackingByClick(Ileft, Iright, 7); // or initTrackingByDetection(Ileft, Iright, 7) after setStereoRig()
  while (grabbing) {
    grab(Ileft, Iright);
    if (!tracker.track(Ileft, Iright)) {       // with a model: tracker.setRobot(robot); tracker.track(Il, Ir, q)
      std::cout << tracker.getReport() << std::endl;
    }
    for (unsigned int k = 0; k < tracker.getNumberOfMarkers(); ++k)
      if (tracker.getState(k) != vpStereoDotTracker::MARKER_LOST)
        s[k].buildFrom(tracker.getLeftPoint(k), tracker.getRightPoint(k));
  }
  \endcode
*/
class VISP_EXPORT vpStereoDotTracker
{
public:
  //! What the last frame gave for a marker.
  enum vpMarkerState {
    MARKER_TRACKED,    //!< Found in both images, as in the frame before.
    MARKER_REDETECTED, //!< Found again in both images after being lost.
    MARKER_LOST        //!< Not found, or not trusted, in at least one image: its position is the prediction.
  };

  //! A tracker with no marker; initialise it with one of the initTracking methods.
  vpStereoDotTracker();

  /*! \name Settings */
  //@{
  /*!
    The weakly calibrated rig whose fundamental matrix checks the correspondences (and pairs the blobs of
    initTrackingByDetection()). Without it (and without a robot) no epipolar check is made.
    \exception vpProjectiveException (notInitializedError) if \e rig has no fundamental matrix yet.
  */
  void setStereoRig(const vpProjectiveStereoRig &rig);
  /*!
    The projective model of the arm that carries the markers: tracker marker \e k is the model's zero-reference marker
    \e markers[k] (0, 1, ... if \e markers is empty). track() with joint values then predicts each blob where the
    model images it (corrected by the last measured offset), and the model's rig checks the correspondences. The robot
    is kept by reference: it must outlive the tracker.
    \exception vpProjectiveException (notInitializedError) if \e robot is not calibrated, (dimensionError) if an index
    is not one of the model's markers or the count differs from the markers already tracked.
  */
  void setRobot(const vpProjectiveRobot &robot, const std::vector<unsigned int> &markers = std::vector<unsigned int>());
  /*!
    Largest distance (px) of a correspondence to its epipolar lines (mean of both images), default 2 px.
    \exception vpProjectiveException (invalidValueError) if not positive and finite.
  */
  void setEpipolarThreshold(double pixels);
  /*!
    Smallest gap (px, edge to edge) between two blobs, default 3 px: closer blobs are about to merge.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setMinimumGap(double pixels);
  /*!
    Radius (px) around its prediction within which a lost blob is searched for, and within which
    initTrackingByDetection() assigns a blob to a model's prediction; default 10 px. \exception vpProjectiveException
    (invalidValueError) if not positive and finite.
  */
  void setSearchRadius(double pixels);
  //! See setEpipolarThreshold().
  double getEpipolarThreshold() const { return m_epipolarThreshold; }
  //! See setMinimumGap().
  double getMinimumGap() const { return m_minimumGap; }
  //! See setSearchRadius().
  double getSearchRadius() const { return m_searchRadius; }
  //@}

  /*! \name Initialisation (on failure each throws vpProjectiveException and leaves the tracker as it was) */
  //@{
  /*!
    Starts tracking one marker per pair (\e left[k], \e right[k]): image points on the markers' blobs, e.g. clicks.
    vpDot2::initTracking() takes the grey level under each point, finds the blob around it and its centre.
    \exception vpProjectiveException (dimensionError) on sizes that differ or no point, (degenerateConfigurationError)
    if a point is not on a blob or two markers are the same or touching blobs, (estimationFailedError) if a pair
    violates the epipolar constraint.
  */
  void initTracking(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                    const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right);
  /*!
    The user clicks each of the \e nbMarkers markers, in the same order, in the left then the right image
    (vpDisplay::getClick()); then initTracking(). The images must be displayed (a vpDisplay attached to each).
    \exception vpProjectiveException (notInitializedError) if an image has no display, or as initTracking().
  */
  void initTrackingByClick(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                           unsigned int nbMarkers);
  /*!
    Automatic initialisation: the bright blobs of each image (pixels brighter than halfway between the median grey
    level and the brightest one, connected) are detected, and exactly \e nbMarkers must be found in each image. They
    are paired by the epipolar geometry (setStereoRig() or setRobot() first): the pairing of least total epipolar
    distance, which must be unambiguous. Marker \e k is then the k-th blob of the left image in raster order (top to
    bottom, then left to right).
    \exception vpProjectiveException (notInitializedError) without a rig, (degenerateConfigurationError) if another
    number of blobs is found or the pairing is ambiguous (two blobs on one epipolar line), (estimationFailedError) if
    a pair is farther than getEpipolarThreshold() from its epipolar line.
  */
  void initTrackingByDetection(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                               unsigned int nbMarkers);
  /*!
    Automatic initialisation with the projective model (setRobot() first): the bright blobs are detected as above and
    each of the model's markers given to setRobot() is assigned, in each image, to the blob nearest to its predicted
    image at the joint values \e q, within getSearchRadius(). Other blobs are ignored.
    \exception vpProjectiveException (notInitializedError) without a robot, (dimensionError) if \e q has not one entry
    per joint, (degenerateConfigurationError) if a marker has no blob near its prediction.
  */
  void initTrackingByDetection(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                               const vpColVector &q);
  /*!
    Keeps only the markers \e which (indices of the tracked markers), in that order: marker k becomes which[k].
    \exception vpProjectiveException (dimensionError) on an index out of range or an empty list.
  */
  void keepMarkers(const std::vector<unsigned int> &which);
  //@}

  /*! \name Tracking */
  //@{
  /*!
    Tracks a new stereo frame, each blob predicted at constant image velocity: its last motion times
    \e motionRatio (this frame's expected motion over the last frame's; 0 before any motion, 1 at a steady pace).
    \return true if every marker was found in both images (MARKER_TRACKED or MARKER_REDETECTED).
    \exception vpProjectiveException (notInitializedError) before an initialisation, (dimensionError) if an image size
    changed, (invalidValueError) if \e motionRatio is negative or not finite.
  */
  bool track(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright, double motionRatio = 1.0);
  /*!
    Tracks a new stereo frame taken at the joint values \e q, each blob predicted by the model of setRobot().
    \exception vpProjectiveException as the other overload, (notInitializedError) without a robot, (dimensionError) if
    \e q has not one entry per joint.
  */
  bool track(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright, const vpColVector &q);
  //@}

  /*! \name Results of the last frame */
  //@{
  //! Number of markers tracked.
  unsigned int getNumberOfMarkers() const { return static_cast<unsigned int>(m_markers.size()); }
  //! The model marker of each tracked marker (0, 1, ... unless setRobot() said otherwise).
  std::vector<unsigned int> getMarkerIndices() const;
  //! State of marker \e k. \exception vpProjectiveException (dimensionError) on a bad index.
  vpMarkerState getState(unsigned int k) const;
  //! Why marker \e k is lost (empty if it is not). \exception vpProjectiveException (dimensionError) on a bad index.
  std::string getFailure(unsigned int k) const;
  //! The reasons of every lost marker, one per line (empty if none).
  std::string getReport() const;
  //! True if every marker was found in both images in the last frame.
  bool isTracked() const;
  //! Centre of marker \e k in the left image (vpDot2::getCog(), or the prediction if lost).
  vpImagePoint getLeftPoint(unsigned int k) const;
  //! Centre of marker \e k in the right image.
  vpImagePoint getRightPoint(unsigned int k) const;
  //! Centres of every marker in the left image.
  std::vector<vpImagePoint> getLeftPoints() const;
  //! Centres of every marker in the right image.
  std::vector<vpImagePoint> getRightPoints() const;
  //! Area (px) of the blob of marker \e k in the left (\e camera 0) or right (1) image at its last detection.
  double getArea(unsigned int k, unsigned int camera) const;
  //! Largest displacement (px) of a blob found in the last frame.
  double getLargestMotion() const { return m_largestMotion; }
  //! Draws the blobs found (contour and centre, in \e color) and the lost markers' predictions (red crosses).
  void display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
               const vpColor &color = vpColor::green) const;
  //@}

private:
  //! One marker in one image.
  struct Blob {
    vpDot2 dot;
    vpImagePoint cog;    // last measurement, or prediction while lost
    vpImagePoint motion; // last frame's displacement (px)
    vpImagePoint offset; // measured minus model-predicted centre at the last detection
    double area = 0.0;   // px, last detection
    unsigned int grayMin = 0, grayMax = 255;
    bool found = false; // found in the last frame
    bool hasOffset = false;
  };
  struct Marker {
    Blob blob[2];
    unsigned int index = 0; // model marker
    vpMarkerState state = MARKER_LOST;
    std::string failure;
  };

  void checkInitialised(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                        const char *method) const;
  void checkMarker(unsigned int k, const char *method) const;
  void checkJoints(const vpColVector &q, const char *method) const;
  bool trackFrame(const vpImage<unsigned char> *const I[2], const std::vector<vpImagePoint> predicted[2],
                  const std::vector<vpImagePoint> *model);
  double epipolarDistance(const vpImagePoint &left, const vpImagePoint &right) const;
  void startMarkers(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                    const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                    const std::vector<unsigned int> &indices, const char *method);

  std::vector<Marker> m_markers;
  const vpProjectiveRobot *m_robot;
  std::vector<unsigned int> m_robotMarkers; // the robot's markers given to setRobot() before any initialisation
  Eigen::Matrix3d m_F;
  bool m_hasF;
  double m_epipolarThreshold;
  double m_minimumGap;
  double m_searchRadius;
  double m_largestMotion;
  unsigned int m_width, m_height;
};

END_VISP_NAMESPACE

#endif
