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
  \file vpSimulatorMarkerRenderer.h
  \brief 8-bit stereo images of lit spherical markers seen by a vpSimulatorStereoRig: exact silhouettes,
  supersampling, optical blur and sensor noise.
*/

#ifndef _vpSimulatorMarkerRenderer_h_
#define _vpSimulatorMarkerRenderer_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cstdint>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/projective/vpSimulatorCameraBuffers.h>
#include <visp3/projective/vpSimulatorImageNoise.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorMarkerRenderer
  \ingroup group_projective_simulator
  \brief Renders what the two cameras of a vpSimulatorStereoRig see of lit spherical markers (infrared LEDs in
  diffusing balls, as motion-capture systems use): bright discs on a dark, uniform scene.

  The image of each ball is its exact perspective silhouette: a ray through the image point \f$ (u, v) \f$,
  \f$ d = ((u - u_0) / p_x, (v - v_0) / p_y, 1) \f$, hits the ball of radius \f$ R \f$ centred at \f$ C \f$ (camera
  frame) when \f$ d \cdot C > 0 \f$ and \f$ (d \cdot C)^2 \ge |d|^2 (|C|^2 - R^2) \f$. Its size follows its depth,
  and a nearer ball hiding a farther one gives the union of their silhouettes (all balls look alike). Each pixel near
  a ball averages \f$ S \times S \f$ such rays (setSupersampling()); the image is then blurred by the optics
  (separable Gaussian, setBlur()), Gaussian sensor noise is added to every pixel (setNoise(), seeded) and the result is
  quantised to 8 bits. A ball behind a camera, or closer to it than twice its radius, is not imaged.

  Only the neighbourhood of the balls is rendered and blurred: elsewhere the image is the uniform background, which
  blurring leaves unchanged, so that a 640 x 480 stereo pair of 7 markers takes about a millisecond.

  Noise: independent Gaussian grey-level noise on every pixel (vpSimulatorImageNoise: a seeded table of 65536 draws,
  each pixel taking one at a pseudo-random index). The left image is rendered before the right one from the same stream,
  so that a renderer built with the same seed and settings renders the same sequence of images.

  \code
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorMarkerRenderer renderer(rig, 1);       // seed 1
  renderer.setMarkerRadius(0.003);                  // 6 mm balls
  vpImage<unsigned char> Ileft, Iright;
  renderer.render(arm.getMarkers(q), Ileft, Iright); // world points (3x1)
  \endcode
*/
class VISP_EXPORT vpSimulatorMarkerRenderer
{
public:
  /*!
    A renderer of the cameras of \e rig (copied), noise seeded by \e seed. Defaults: 3 mm balls, background grey level
    30, lit balls 220, blur 0.8 px, noise 4 grey levels, 8 x 8 rays per pixel.
  */
  explicit vpSimulatorMarkerRenderer(const vpSimulatorStereoRig &rig, long seed = 1);

  /*! \name Settings (each throws vpProjectiveException, invalidValueError, on a bad value and then changes nothing) */
  //@{
  //! Radius of every ball, metres (> 0, finite).
  void setMarkerRadius(double radius);
  //! Grey levels of the scene and of a lit ball (each in [0, 255]). Restarts the noise stream.
  void setGrayLevels(double background, double marker);
  //! Standard deviation of the optical blur in pixels (>= 0; 0: no blur, at most 10).
  void setBlur(double sigma);
  //! Standard deviation of the sensor noise in grey levels (>= 0, at most 100). Restarts the noise stream.
  void setNoise(double sigma);
  //! Rays per pixel along each axis on a silhouette's edge (1 to 32).
  void setSupersampling(unsigned int rays);
  //! Restarts the noise stream from \e seed.
  void setSeed(long seed);
  //@}

  //! Radius of the balls (m).
  double getMarkerRadius() const { return m_radius; }
  //! Grey level of the scene.
  double getBackgroundLevel() const { return m_background; }
  //! Grey level of a lit ball.
  double getMarkerLevel() const { return m_marker; }
  //! Standard deviation of the blur (px).
  double getBlur() const { return m_blur; }
  //! Standard deviation of the sensor noise (grey levels).
  double getNoise() const { return m_noise; }
  //! Rays per pixel along each axis.
  unsigned int getSupersampling() const { return m_supersampling; }
  //! The rig whose cameras are rendered.
  const vpSimulatorStereoRig &getStereoRig() const { return m_rig; }

  /*!
    Renders the balls centred at the world points \e wX (3x1, or 4x1 with last entry 1) in both cameras. The images
    are resized to the rig's image size.
    \exception vpProjectiveException (dimensionError or nonFiniteValueError) if a point is not 3x1 / 4x1 or not finite;
    the images and the noise stream are then unchanged.
  */
  void render(const std::vector<vpColVector> &wX, vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright);

  /*!
    Radius in pixels of the silhouette of a ball at depth \e depth metres on the optical axis of the left camera,
    \f$ p_x R / \sqrt{Z^2 - R^2} \f$ (0 if the ball is not imaged).
  */
  double getImageRadius(double depth) const;

private:
  struct Ball {
    double x, y, z, c2;         // centre in the camera frame (m), |C|^2 - R^2
    double u, v, reach;         // image of the centre, radius (px) beyond which no pixel sees the ball
    int imin, imax, jmin, jmax; // pixel box of the silhouette
  };

  void renderCamera(vpSimulatorCameraBuffers &camera, const std::vector<vpColVector> &wX, vpImage<unsigned char> &I);
  void resetNoise();
  void resetBuffers();

  vpSimulatorStereoRig m_rig;
  double m_radius;
  double m_background;
  double m_marker;
  double m_blur;
  double m_noise;
  unsigned int m_supersampling;
  long m_seed;
  std::vector<double> m_kernel;          // half of a normalised Gaussian kernel; m_kernel[0] is its centre
  vpSimulatorCameraBuffers m_cameras[2]; // left, right (uniform background outside the balls' boxes)
  vpSimulatorImageNoise m_imageNoise;
};

END_VISP_NAMESPACE

#endif
