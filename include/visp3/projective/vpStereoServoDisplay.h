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
  \file vpStereoServoDisplay.h
  \brief What a stereo servo loop shows while it runs: both camera images side by side with the tags or markers, the
  current and desired features and their image paths, and a vpPlot of the image error and of the joints.
*/

#ifndef _vpStereoServoDisplay_h_
#define _vpStereoServoDisplay_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>

BEGIN_VISP_NAMESPACE

class vpDisplay;
class vpFeatureStereoPoint;
class vpFont;
class vpPlot;

/*!
  \class vpStereoServoDisplay
  \ingroup group_projective
  \brief The live view of a stereo servo loop, as ViSP's tutorials show theirs: one window with the left and the
  right image side by side, the detected tags or tracked markers, the desired features \f$ s^* \f$, the current
  features \f$ s \f$ and their paths, a caption; and a vpPlot window of the image error and of the joints.

  The picture is \f$ (2 w + 10) \times h \f$ pixels: the left image, a 10 px dark gap, the right image; a point
  \f$ (u', v') \f$ of the right image is drawn at \f$ (u' + w + 10, v') \f$. The overlay is drawn into the picture
  itself (vpImageDraw, vpFont), each image clipped to its own half, so that the picture exists without any display:
  getPicture() and write() give the figure of a headless run. With a window, flush() shows the picture in it
  (vpDisplayX, vpDisplayGDI, vpDisplayOpenCV or vpDisplayGTK, the first one this ViSP has) and plot() adds a point
  to each curve of the vpPlot window under it. Without a window every call but the drawing into the picture does
  nothing, so that the same loop runs headless (ViSP's \c -d).

  What is drawn, a point \f$ (u, v) \f$ at the pixel of the rounded coordinates:
  - tags (displayTags()): a yellow outline through the corners of each tag and its id;
  - markers (displayMarkers()): a circle of radius 6 px, yellow unless told;
  - features (displayFeature()): \f$ s^* \f$ as a red cross of 15 px, \f$ s \f$ as a green cross of 9 px drawn over
    it (at convergence the red tips stay visible around the green cross), and the path of \f$ s \f$ since
    clearTrajectories() as a green polyline;
  - captions (displayText()): white lines on black from the top left corner.

  A servo loop, its images from two grabbers (vpStereoImageSource) or a simulated cell:
  \code
  vpStereoServoDisplay display;
  display.init(width, height, opt_display && vpStereoServoDisplay::hasDisplay());
  while (source.acquire(Ileft, Iright)) {
    tags.detect(Ileft, Iright); // s[k].buildFrom(...)
    display.display(Ileft, Iright);
    display.displayTags(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints());
    for (unsigned int k = 0; k < 4; ++k) {
      display.displayFeature(k, s[k], s_star[k]);
    }
    display.displayText("iteration " + std::to_string(it));
    display.flush();
    qdot = task.computeControlLaw(q);
    display.plot(task.getError(), q);
  }
  display.write("stereo-end.png"); // what the window shows (the picture when headless)
  if (opt_click_allowed) {
    display.getClick(); // waits only if the window is open
  }
  \endcode

  Every input is checked before anything is drawn: a bad one throws a vpProjectiveException and the display stays as
  it was.
*/
class VISP_EXPORT vpStereoServoDisplay
{
public:
  //! A display of no size yet: init() gives it one.
  vpStereoServoDisplay();
  //! The same as init(\e width, \e height, \e window, \e x, \e y, \e title) after the default constructor.
  vpStereoServoDisplay(unsigned int width, unsigned int height, bool window = hasDisplay(), int x = 0, int y = 0,
                       const std::string &title = "Left and right cameras");
  //! Closes the windows.
  ~vpStereoServoDisplay();
  vpStereoServoDisplay(const vpStereoServoDisplay &) = delete;
  vpStereoServoDisplay &operator=(const vpStereoServoDisplay &) = delete;

  /*!
    True if windows can be opened here: ViSP has a display (VISP_HAVE_DISPLAY) and, on an X11 system, the environment
    variable DISPLAY names a server. ViSP's examples open their windows when this holds and \c -d was not given.
  */
  static bool hasDisplay();

  /*!
    Prepares a picture for two images of \e width x \e height pixels (the trajectories and the plot cleared). If
    \e window and hasDisplay(), opens its window at (\e x, \e y) on the screen with \e title; the plot window opens
    under it at the first plot().
    \exception vpProjectiveException (invalidValueError) if \e width or \e height is 0; vpDisplayException if the
    window cannot be opened (no X server at DISPLAY).
  */
  void init(unsigned int width, unsigned int height, bool window = hasDisplay(), int x = 0, int y = 0,
            const std::string &title = "Left and right cameras");
  //! True if the picture's window is open.
  bool isOpen() const { return m_window != nullptr; }

  /*! \name One frame: the images, then the overlay, then flush() */
  //@{
  /*!
    Starts a frame: copies \e Ileft and \e Iright into the picture (the previous frame's overlay and captions go).
    \exception vpProjectiveException (notInitializedError) before init(); (dimensionError) if an image is not of the
    size given to init().
  */
  void display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright);
  //! Starts a frame on white images: for pixels without images (simulated projections, as ViSP's tutorial-ibvs-4pts).
  void display();
  /*!
    Draws the tags whose corners are \e left and \e right, identified by \e ids = 4 x tag id + corner index
    (vpStereoAprilTagDetector::getIds()): an outline joining the corners c and c + 1 (mod 4) of a tag seen in both,
    and the tag id.
    \exception vpProjectiveException (dimensionError) if the sizes differ; (invalidValueError) if an id is negative;
    (nonFiniteValueError) if a point is not finite.
  */
  void displayTags(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                   const std::vector<vpImagePoint> &right);
  /*!
    Draws a circle around each marker image \e left[k] and \e right[k] (e.g. vpStereoDotTracker's), in \e color.
    \exception vpProjectiveException (dimensionError) if the sizes differ; (nonFiniteValueError) if a point is not
    finite.
  */
  void displayMarkers(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                      const vpColor &color = vpColor::yellow);
  /*!
    Draws feature \e i: its desired value \e s_star and, if \e seen, its current value \e s, which extends the path
    of feature \e i (a point equal to the path's last one is not added again); the path is drawn in any case.
  */
  void displayFeature(unsigned int i, const vpFeatureStereoPoint &s, const vpFeatureStereoPoint &s_star,
                      bool seen = true);
  //! Writes \e text on the next caption line (the first line at the top left corner of the left image).
  void displayText(const std::string &text);
  //! Shows the picture in the window, if it is open.
  void flush();
  //@}

  /*!
    Adds one point, at x = the number of plot() calls so far, to each curve of the plot window (if the window is
    open): graph 0, the image error of each stereo point, the RMS of its 4 coordinates in \e e (s - s*, 4 rows per
    point, as vpServoProjective::getError(); the unit of \e e); graph 1, each joint of \e q (encoder units: rad or m;
    no graph if \e q is empty). The first call fixes the number of curves.
    \exception vpProjectiveException (dimensionError) if the size of \e e is 0 or not a multiple of 4, or if the
    sizes differ from the first call's; (nonFiniteValueError) if a value is not finite.
  */
  void plot(const vpColVector &e, const vpColVector &q);

  /*!
    Waits for a click in the picture's window if \e blocking (ViSP's examples do at their end unless \c -c was
    given); returns true if there was one. Without a window returns false at once.
  */
  bool getClick(bool blocking = true);
  //! Forgets the features' paths (e.g. before a new task).
  void clearTrajectories()
  {
    m_paths[0].clear();
    m_paths[1].clear();
  }

  //! The picture as last composed by flush(): both images with the overlay, as the window shows it.
  const vpImage<vpRGBa> &getPicture() const { return m_picture; }
  /*!
    What the window shows, read back from the display (vpDisplay::getImage()).
    \exception vpProjectiveException (notInitializedError) if no window is open.
  */
  void getWindowImage(vpImage<vpRGBa> &I) const;
  /*!
    Writes what the window shows to \e file (vpImageIo: PNG, JPEG, PPM... by the extension), or the picture if no
    window is open; makes the file's folder if needed.
    \exception vpProjectiveException (fileError) if the file cannot be written or this ViSP has no io module.
  */
  void write(const std::string &file) const;
  /*!
    Writes what the plot window shows to \e file and returns true; returns false and writes nothing if the plot window
    is not open (no window, or no plot() yet).
    \exception vpProjectiveException (fileError) as write().
  */
  bool writePlot(const std::string &file) const;

private:
  //! One image and its half of the overlay.
  struct vpSide {
    vpImage<vpRGBa> I;
    unsigned int shift; //!< the column of the picture where it starts
  };

  void requireInit(const char *method) const;

  vpSide m_side[2];
  vpImage<vpRGBa> m_picture;
  std::vector<std::vector<vpImagePoint>> m_paths[2]; //!< per side, per feature
  unsigned int m_captionLines;
  unsigned int m_plotted;    //!< plot() calls since init()
  unsigned int m_plotPoints; //!< stereo points of the first plot()
  unsigned int m_plotJoints; //!< joints of the first plot()
  int m_x, m_y;              //!< where the window is
  std::unique_ptr<vpFont> m_font;
  std::unique_ptr<vpDisplay> m_window;
  std::unique_ptr<vpPlot> m_plot;
};

END_VISP_NAMESPACE

#endif
