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
  \file vpStereoAprilTagDetector.h
  \brief AprilTag corners as stereo markers: vpDetectorAprilTag in both images, corners paired by tag id and corner
  index, refined to sub-pixel accuracy, optionally checked against the rig's epipolar geometry.
*/

#ifndef _vpStereoAprilTagDetector_h_
#define _vpStereoAprilTagDetector_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#if defined(VISP_HAVE_APRILTAG) // ViSP built with its AprilTag 3 (3rdparty/apriltag, on by default)

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/detection/vpDetectorAprilTag.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveStereoRig;

/*!
  \class vpStereoAprilTagDetector
  \ingroup group_projective
  \brief Detects AprilTags in a stereo pair and returns their corners seen in both images, identified by
  \f$ 4 \times \mathrm{tag\ id} + \mathrm{corner\ index} \f$.

  Corner index: vpDetectorAprilTag's order. In the tag's own frame (ViSP's object frame: \f$ x \f$ along the printed
  pattern's columns, \f$ y \f$ along its rows, origin at the centre, \f$ s \f$ the black square's side) corner 0 is at
  \f$ (-s/2, s/2) \f$, 1 at \f$ (s/2, s/2) \f$, 2 at \f$ (s/2, -s/2) \f$, 3 at \f$ (-s/2, -s/2) \f$: the outer corners
  of the black border.

  Points are in ViSP's pixel convention, the centre of pixel (i, j) at (u, v) = (j, i). vpDetectorAprilTag (AprilTag
  3) returns them half a pixel further on both axes (its pixel centres are at (j + 1/2, i + 1/2)): detect() removes
  that offset.

  Refinement (setRefinement(), on by default): each of the 4 outer edges of the black border is relocated at points
  2 px apart, away from the corners, as the centroid of the positive intensity derivative across it (bilinear
  samples every 0.5 px within 3 px, black inside, white outside), a line is fitted to those points (total least
  squares), and each corner becomes the intersection of its two edges' lines; again if a corner moved by 0.1 px or more.
  A corner that would move by more than 2 px keeps vpDetectorAprilTag's position. AprilTag's own edge refinement is then
  redundant and off. Measured accuracy: \ref page_estimation_tags.

  Tracking: setPredictedRegions() gives where the tags are expected (e.g. the model's predictions, or the last
  detection's corners); detect() then runs vpDetectorAprilTag only in the box around each predicted tag (grown by
  setRegionMargin(), by the quiet zone and 2 px), keeps that tag there and shifts its corners back. A predicted tag not
  found in its box is searched for in the whole image (once per image, for all such tags): tracking costs a full
  detection on the frames where a tag escaped its box, and loses no tag that detection finds. Tags that were not
  predicted are not looked for: clearPredictedRegions() returns to full-image detection.

  A tag id seen twice in one image (two printed copies) is ambiguous and dropped.

  \code
  vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
  tags.setStereoRig(rig);                         // optional: pairs off their epipolar lines are dropped
  unsigned int n = tags.detect(Ileft, Iright);    // corners found in both images
  std::vector<int> ids = tags.getIds();           // 4 * tag id + corner index, ascending
  std::vector<vpImagePoint> l = tags.getLeftPoints(), r = tags.getRightPoints(); // in the order of ids
  tags.setPredictedRegions(ids, l, r);            // next frames: search near these corners only
  \endcode
*/
class VISP_EXPORT vpStereoAprilTagDetector
{
public:
  //! A detector of the tags of \e family (vpDetectorAprilTag's names): one thread, decimation 1.5, refinement on, no
  //! epipolar check, full-image detection.
  explicit vpStereoAprilTagDetector(vpDetectorAprilTag::vpAprilTagFamily family = vpDetectorAprilTag::TAG_36h11);

  /*! \name Settings (each throws vpProjectiveException on a bad value and then changes nothing) */
  //@{
  /*!
    Checks every pair against the epipolar geometry of \e rig (copied): a corner whose left or right image is farther
    than getEpipolarThreshold() from the epipolar line of the other is dropped.
    \exception vpProjectiveException (notInitializedError) if \e rig has no fundamental matrix yet.
  */
  void setStereoRig(const vpProjectiveStereoRig &rig);
  //! No epipolar check.
  void clearStereoRig() { m_useRig = false; }
  //! Largest epipolar distance (px) of a kept pair (> 0; default 2 px).
  void setEpipolarThreshold(double pixels);
  /*!
    vpDetectorAprilTag's quad decimation (1 to 8; default 1.5): the quads are searched in an image decimated by this
    factor, the refinement then works at full resolution (same accuracy). 1.5 finds every tag of 25 px or more
    (\ref page_estimation_tags); give 1 for smaller tags.
  */
  void setDecimation(double decimation);
  //! Sub-pixel refinement of the corners (class description), on by default.
  void setRefinement(bool refine) { m_refine = refine; }
  //! Threads of vpDetectorAprilTag (1 to 64; default 1).
  void setNbThreads(unsigned int threads);
  //@}

  /*! \name Tracking */
  //@{
  /*!
    Where the tags are expected in the next images: \e ids (4 * tag id + corner index, as getIds()) and their
    predicted \e left and \e right images. A tag is searched in the box of its predicted corners in each image; a tag
    with none of its corners among \e ids is not searched. Kept until cleared or replaced.
    \exception vpProjectiveException (dimensionError, nonFiniteValueError, invalidValueError) if the sizes differ, a
    point is not finite or an id is negative.
  */
  void setPredictedRegions(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                           const std::vector<vpImagePoint> &right);
  //! Full-image detection again.
  void clearPredictedRegions();
  //! Pixels added around each predicted tag's box (>= 0; default 10), for the motion between frames.
  void setRegionMargin(double pixels);
  //! True while predicted regions are set.
  bool hasPredictedRegions() const { return !m_predicted.empty(); }
  //@}

  /*!
    Detects the tags in both images and pairs their corners.
    \return the number of corners found in both images (and kept by the epipolar check).
    \exception vpProjectiveException (dimensionError) if an image is empty or the two differ in size; the previous
    results are then kept.
  */
  unsigned int detect(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright);

  //! One per corner: 4 * tag id + corner index, ascending.
  const std::vector<int> &getIds() const { return m_ids; }
  //! The corners in the left image, in the order of getIds().
  const std::vector<vpImagePoint> &getLeftPoints() const { return m_left; }
  //! The corners in the right image, in the order of getIds().
  const std::vector<vpImagePoint> &getRightPoints() const { return m_right; }
  //! Corners seen in both images but dropped by the epipolar check in the last detect().
  unsigned int getNbEpipolarRejections() const { return m_rejected; }
  //! Largest epipolar distance of a kept pair (px).
  double getEpipolarThreshold() const { return m_epipolarThreshold; }

private:
  //! One tag in one image: its id and 4 corners (ViSP's convention).
  struct Tag {
    int id;
    vpImagePoint corners[4];
  };
  struct Box {
    int i0, j0, i1, j1; // first and last rows and columns
    int id;             // the tag kept in the box; -1: all
  };

  Box box(const vpImage<unsigned char> &I, int side, size_t t) const;
  void detectImage(const vpImage<unsigned char> &I, int side, std::vector<Tag> &tags);
  void detectIn(const vpImage<unsigned char> &I, const Box &box, std::vector<Tag> &tags);
  void refine(const vpImage<unsigned char> &I, Tag &tag) const;

  vpDetectorAprilTag m_detector;
  vpMatrix m_F;
  bool m_useRig;
  double m_epipolarThreshold;
  bool m_refine;
  double m_margin;
  double m_decimation;                         // setDecimation()
  std::vector<int> m_predicted;                // tag ids searched in regions
  std::vector<vpImagePoint> m_predictedBox[2]; // per predicted tag: (min, max) corners, per image
  vpImage<unsigned char> m_crop;
  std::vector<int> m_ids;
  std::vector<vpImagePoint> m_left, m_right;
  unsigned int m_rejected;
};

END_VISP_NAMESPACE

#endif // VISP_HAVE_APRILTAG

#endif
