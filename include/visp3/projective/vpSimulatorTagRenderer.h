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
  \file vpSimulatorTagRenderer.h
  \brief 8-bit stereo images of printed AprilTags (36h11) seen by a vpSimulatorStereoRig: exact perspective,
  supersampling, optical blur, sensor noise, lighting change and an occluder.
*/

#ifndef _vpSimulatorTagRenderer_h_
#define _vpSimulatorTagRenderer_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cstdint>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpSimulatorCameraBuffers.h>
#include <visp3/projective/vpSimulatorImageNoise.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorTagRenderer
  \ingroup group_projective_simulator
  \brief Renders what the two cameras of a vpSimulatorStereoRig see of printed AprilTags of the 36h11 family
  (ids 0 to 31) on a mid-grey scene.

  Frames: \c w the world (the rig's, vpSimulatorStereoRig), \c b the body that carries the tags (e.g. the arm's
  tool: setBodyPose() moves them all), \c t a tag. Tag frame (ViSP's object frame of vpDetectorAprilTag): origin at the
  tag's centre, \f$ x \f$ along the columns of the printed pattern (to the right when the tag is read upright), \f$ y
  \f$ along its rows (downwards), \f$ z = x \times y \f$ into the tag, away from a reader facing the print. The \e size
  \f$ s \f$ of a tag is the side of its black square (ViSP's \c tagSize); the pattern is the family's 10 x 10 cells of
  side \f$ s/8 \f$: a white quiet zone of one cell, the black border, the 6 x 6 data cells. Its corners, in
  vpDetectorAprilTag's order (getCorners(), getImageCorners()), are at \f$ (x, y) = \f$ 0: \f$ (-s/2, s/2) \f$, 1: \f$
  (s/2, s/2) \f$, 2: \f$ (s/2, -s/2) \f$, 3: \f$ (-s/2, -s/2) \f$.

  Each pixel is the area \f$ [j - 1/2, j + 1/2] \times [i - 1/2, i + 1/2] \f$ around its centre
  \f$ (u, v) = (j, i) \f$ (ViSP's convention). Its value is exact perspective: the ray through an image point meets
  the tag's plane at a point read in the tag's cells (\f$ {}^t x \simeq (K [r_1\ r_2\ t])^{-1} (u, v, 1) \f$, the
  nearest tag wins). A pixel whose four corners fall in one cell, or in a block of 2 x 2 cells of one colour (both
  convex), takes that colour; the others (on an edge) average \f$ N = S^2 \f$ rays (setSupersampling()) of a rank-1
  lattice, each on its own row and column of \f$ 1/N \f$ px. Then, in order: Gaussian optical blur (setBlur()), lighting
  \f$ g = o + a (1 + b_u (u - W/2)/W + b_v (v - H/2)/H)\, g \f$ (setLighting()), Gaussian sensor noise (setNoise(),
  vpSimulatorImageNoise) and 8-bit quantisation. Only the
  tags' boxes are rendered and blurred (speed: tests/benchmark/benchmarkAprilTag).

  A tag is drawn when its printed side faces the camera and its whole quiet zone is in front of it (depth > 1 mm);
  the occluder (setOccluder()), a dark ball, is drawn over the tags.

  \code
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorTagRenderer renderer(rig, 1);
  renderer.addTag(3, 0.04, vpHomogeneousMatrix()); // id 3, 4 cm black square at the fixation, facing the rig (the
                                                   // tag's z along the world +Z, the rig's viewing direction)
  vpImage<unsigned char> Ileft, Iright;
  renderer.render(Ileft, Iright);
  \endcode
*/
class VISP_EXPORT vpSimulatorTagRenderer
{
public:
  //! Largest id rendered: the table holds the first 32 codes of the 36h11 family.
  static const int maxTagId = 31;

  /*!
    A renderer of the cameras of \e rig (copied), noise seeded by \e seed, no tag. Defaults: background grey level
    128, black 30, white 220, blur 0 px, noise 1 grey level, 4 x 4 rays per edge pixel, no lighting change, no
    occluder.
  */
  explicit vpSimulatorTagRenderer(const vpSimulatorStereoRig &rig, long seed = 1);

  /*! \name The tags */
  //@{
  /*!
    Adds the tag \e id (0 to maxTagId) of black-square side \e size metres at pose \e bMt in the body frame \c b
    (setBodyPose(); the world frame until then). Ids may repeat (two printed copies).
    \return its index for setTagPose().
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a bad id, size or pose.
  */
  unsigned int addTag(int id, double size, const vpHomogeneousMatrix &bMt);
  //! Moves tag \e index to \e bMt (body frame). \exception vpProjectiveException on a bad index or a non-finite pose.
  void setTagPose(unsigned int index, const vpHomogeneousMatrix &bMt);
  /*!
    Pose \e wMb in the world of the body that carries the tags (e.g. the arm's tool, wMb = wMe(q) with the tags
    placed on its faces by addTag()): the tags move with it. Identity by default.
    \exception vpProjectiveException (nonFiniteValueError) on a non-finite pose.
  */
  void setBodyPose(const vpHomogeneousMatrix &wMb);
  //! Pose of the body in the world.
  const vpHomogeneousMatrix &getBodyPose() const { return m_wMb; }
  //! Removes every tag.
  void clearTags() { m_tags.clear(); }
  //! Number of tags.
  unsigned int getNbTags() const { return static_cast<unsigned int>(m_tags.size()); }
  //! Id of tag \e index.
  int getTagId(unsigned int index) const { return tag(index, "getTagId()").id; }
  //! Black-square side (m) of tag \e index.
  double getTagSize(unsigned int index) const { return tag(index, "getTagSize()").size; }
  //! Pose of tag \e index in the world: getBodyPose() times its pose in the body.
  vpHomogeneousMatrix getTagPose(unsigned int index) const { return m_wMb * tag(index, "getTagPose()").bMt; }
  //! World coordinates (3x1) of the 4 corners of tag \e index, in vpDetectorAprilTag's order (class description).
  std::vector<vpColVector> getCorners(unsigned int index) const;
  /*!
    Noise-free images of the 4 corners of tag \e index (ViSP's pixel convention): the truth the detector is tested
    against. \return true if the tag is drawn in both images (facing, in front) and its corners are inside them.
  */
  bool getImageCorners(unsigned int index, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) const;
  //@}

  /*! \name Settings (each throws vpProjectiveException, invalidValueError, on a bad value and then changes nothing) */
  //@{
  //! Grey levels of the scene, of the black and of the white print (each in [0, 255]).
  void setGrayLevels(double background, double black, double white);
  //! Standard deviation of the optical blur in pixels (0 to 10; 0: no blur).
  void setBlur(double sigma);
  //! Standard deviation of the sensor noise in grey levels (0 to 100). Restarts the noise stream.
  void setNoise(double sigma);
  //! Rays per edge pixel along each axis (1 to 32).
  void setSupersampling(unsigned int rays);
  /*!
    Lighting (class description): gain \e gain (0 to 10), offset \e offset grey levels (-255 to 255), relative gain
    slopes \e gradientU, \e gradientV across the image width and height (-1 to 1). (1, 0, 0, 0): no change.
  */
  void setLighting(double gain, double offset, double gradientU = 0.0, double gradientV = 0.0);
  /*!
    A dark ball of radius \e radius metres centred at the world point \e wC (3x1), of grey level \e level, drawn
    over the tags in both images. \exception vpProjectiveException on a bad size or value.
  */
  void setOccluder(const vpColVector &wC, double radius, double level = 15.0);
  //! No occluder.
  void clearOccluder() { m_occluderRadius = 0.0; }
  //! Restarts the noise stream from \e seed.
  void setSeed(long seed);
  //@}

  //! Standard deviation of the blur (px).
  double getBlur() const { return m_blur; }
  //! Standard deviation of the sensor noise (grey levels).
  double getNoise() const { return m_noise; }
  //! The rig whose cameras are rendered.
  const vpSimulatorStereoRig &getStereoRig() const { return m_rig; }

  /*!
    Renders the tags in both cameras, left first (one noise stream). The images are resized to the rig's size.
  */
  void render(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright);

private:
  struct Tag {
    int id;
    double size;
    vpHomogeneousMatrix bMt;
    uint8_t cells[100]; // 10 x 10, row-major (row = tag y), 1 = white
  };
  //! A tag as one camera sees it: pixel -> cell homography, pixel box.
  struct View {
    double H[9];                // (gx, gy, 1/Z) ~ H (u, v, 1), gx, gy in cells from the quiet zone's corner
    int imin, imax, jmin, jmax; // pixel box of the quiet zone (and of the occluder's silhouette)
    const Tag *tag;             // null for the occluder
  };

  //! Tag \e index; \exception vpProjectiveException (invalidValueError), naming \e method, if there is none.
  const Tag &tag(unsigned int index, const char *method) const;
  bool view(const vpSimulatorCameraBuffers &camera, const Tag &tag, View &v) const;
  double level(const vpSimulatorCameraBuffers &camera, const std::vector<const View *> &views, double u, double v,
               int &label) const;
  void renderCamera(vpSimulatorCameraBuffers &camera, vpImage<unsigned char> &I);
  void resetNoise();

  vpSimulatorStereoRig m_rig;
  std::vector<Tag> m_tags;
  vpHomogeneousMatrix m_wMb;
  double m_background, m_black, m_white;
  double m_blur;
  double m_noise;
  unsigned int m_supersampling;
  double m_gain, m_offset, m_gradientU, m_gradientV;
  vpColVector m_occluder;
  double m_occluderRadius, m_occluderLevel;
  long m_seed;
  std::vector<double> m_kernel;
  vpSimulatorCameraBuffers m_cameras[2]; // left, right
  vpSimulatorImageNoise m_imageNoise;
  std::vector<int> m_labels;
  std::vector<View> m_views;
  std::vector<const View *> m_near;
};

END_VISP_NAMESPACE

#endif
