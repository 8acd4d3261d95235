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
  Tests of vpStereoServoDisplay: rendered AprilTags detected over a few frames of a moving tool, drawn with their
  corners as features; the picture has the overlay's colour at every detected corner, feature, desired feature and
  path point (right image shifted by its width and the gap), and the camera images pixel for pixel everywhere else;
  headless and in a window of an X server the test starts (Xvfb), whose content read back (vpDisplay::getImage) is
  the picture; the plot window. The AprilTag tutorial run with its display on under Xvfb: it exits 0 by itself (-c)
  and the window it saved shows s* and the converged features where it printed s*. Bad input is refused.
*/

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpSimulatorTagRenderer.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#include "vpProjectiveSessionTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const vpRGBa kYellow(255, 255, 0), kRed(255, 0, 0), kGreen(0, 255, 0);
const unsigned int kGap = 10; // the class's dark columns between the images

//! Where the display draws \e p of image \e side (0 left, 1 right) in a picture of images \e width wide.
vpImagePoint drawn(const vpImagePoint &p, unsigned int side, unsigned int width)
{
  return vpImagePoint(std::round(p.get_i()), std::round(p.get_j()) + side * (width + kGap));
}

bool sameColour(const vpRGBa &a, const vpRGBa &b)
{
  return a.R == b.R && a.G == b.G && a.B == b.B;
}

//! The same size and colours (vpImage::operator== of ViSP 3.5 is not const).
bool samePicture(const vpImage<vpRGBa> &A, const vpImage<vpRGBa> &B)
{
  if (A.getWidth() != B.getWidth() || A.getHeight() != B.getHeight()) {
    return false;
  }
  for (unsigned int k = 0; k < A.getSize(); ++k) {
    if (!sameColour(A.bitmap[k], B.bitmap[k])) {
      return false;
    }
  }
  return true;
}

::testing::AssertionResult colourAt(const vpImage<vpRGBa> &I, const vpImagePoint &p, const vpRGBa &expected,
                                    const std::string &what)
{
  const vpRGBa &c = I[static_cast<unsigned int>(p.get_i())][static_cast<unsigned int>(p.get_j())];
  if (sameColour(c, expected)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << what << " at (u, v) = (" << p.get_j() << ", " << p.get_i() << "): ("
                                       << int(c.R) << ", " << int(c.G) << ", " << int(c.B) << "), not ("
                                       << int(expected.R) << ", " << int(expected.G) << ", " << int(expected.B) << ")";
}

#if defined(VISP_HAVE_APRILTAG)
/*
  Three 4 cm tags (ids 0 to 2) on a tool 1 m in front of the paper's rig, moving 3 mm along x and 2 mm along y per
  frame for 6 frames; tag 1's corners are the features, s* their images in the first frame. Everything the display
  was given is kept for the checks.
*/
struct TagScene {
  unsigned int width = 0, height = 0;
  vpImage<unsigned char> Ileft, Iright;
  std::vector<int> ids;                  // the last frame's detection
  std::vector<vpImagePoint> left, right; // idem
  vpFeatureStereoPoint s[4], s_star[4];  // tag 1's corners (ids 4 to 7): last frame, first frame
  std::vector<vpImagePoint> path[2];     // every feature's image in every frame, per side
  std::vector<vpImagePoint> box[2];      // every corner of every frame, per side: where the overlay can be

  void run(vpStereoServoDisplay &display, bool window)
  {
    const vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
    width = rig.getWidth();
    height = rig.getHeight();
    vpSimulatorTagRenderer renderer(rig, 3);
    for (int id = 0; id < 3; ++id) {
      renderer.addTag(id, 0.04, vpHomogeneousMatrix(-0.07 + 0.07 * id, 0.02 * (id - 1), 0.0, 0.2, -0.15, 0.3 * id));
    }
    vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
    display.init(width, height, window);
    for (unsigned int frame = 0; frame < 6; ++frame) {
      renderer.setBodyPose(vpHomogeneousMatrix(0.003 * frame, 0.002 * frame, 0.0, 0.0, 0.0, 0.0));
      renderer.render(Ileft, Iright);
      ASSERT_EQ(tags.detect(Ileft, Iright), 12u) << "frame " << frame;
      ids = tags.getIds();
      left = tags.getLeftPoints();
      right = tags.getRightPoints();
      for (unsigned int k = 0; k < 4; ++k) {
        s[k].buildFrom(left[4 + k], right[4 + k]); // ids are ascending: tag 1's corners are the 5th to 8th
        if (frame == 0) {
          s_star[k] = s[k];
        }
        path[0].push_back(left[4 + k]);
        path[1].push_back(right[4 + k]);
      }
      box[0].insert(box[0].end(), left.begin(), left.end());
      box[1].insert(box[1].end(), right.begin(), right.end());
      display.display(Ileft, Iright);
      display.displayTags(ids, left, right);
      for (unsigned int k = 0; k < 4; ++k) {
        display.displayFeature(k, s[k], s_star[k]);
      }
      display.displayText("frame " + std::to_string(frame));
      display.flush();
      vpColVector e, q(6, 0.1 * frame);
      for (unsigned int k = 0; k < 4; ++k) {
        e.stack(s[k].error(s_star[k]));
      }
      display.plot(e, q);
    }
    ASSERT_EQ(ids, std::vector<int>({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  }

  //! The Chebyshev distance (px) from \e p to the nearest of \e points.
  static double distance(const vpImagePoint &p, const std::vector<vpImagePoint> &points)
  {
    double d = 1.0e9;
    for (const vpImagePoint &q : points) {
      d = std::min(d, std::max(std::fabs(p.get_i() - q.get_i()), std::fabs(p.get_j() - q.get_j())));
    }
    return d;
  }

  /*
    The picture \e I shows the scene: the overlay's colour where something was drawn, the camera images (or the gap)
    pixel for pixel everywhere else.
  */
  void check(const vpImage<vpRGBa> &I) const
  {
    ASSERT_EQ(I.getWidth(), 2 * width + kGap);
    ASSERT_EQ(I.getHeight(), height);
    for (unsigned int c = 0; c < 2; ++c) {
      const std::vector<vpImagePoint> &corners = c == 0 ? left : right;
      std::vector<vpImagePoint> desired, current;
      for (unsigned int k = 0; k < 4; ++k) {
        desired.push_back(c == 0 ? s_star[k].getLeft() : s_star[k].getRight());
        current.push_back(c == 0 ? s[k].getLeft() : s[k].getRight());
        // The tracked corners moved: the current feature's cross does not hide s*.
        ASSERT_GT(distance(current.back(), {desired.back()}), 8.0) << "corner " << k;
      }
      for (unsigned int k = 0; k < 4; ++k) {
        EXPECT_TRUE(colourAt(I, drawn(current[k], c, width), kGreen, "feature " + std::to_string(k)));
        EXPECT_TRUE(colourAt(I, drawn(desired[k], c, width), kRed, "desired feature " + std::to_string(k)));
      }
      for (size_t k = 0; k < corners.size(); ++k) {
        if (k < 4 || k >= 8) { // the corners of tags 0 and 2 (tag 1's are the features)
          EXPECT_TRUE(colourAt(I, drawn(corners[k], c, width), kYellow, "tag corner " + std::to_string(k)));
        }
      }
      for (const vpImagePoint &p : path[c]) { // where no cross covers the path
        if (distance(p, desired) > 7.0 && distance(p, current) > 4.0) {
          EXPECT_TRUE(colourAt(I, drawn(p, c, width), kGreen, "path point"));
        }
      }
    }
    // Everywhere else: the images, each in its half, and the gap. The overlay stays in the tags' box (grown by the
    // room of the ids above the tags) and the caption's corner.
    vpImagePoint lo[2], hi[2];
    for (unsigned int c = 0; c < 2; ++c) {
      lo[c] = hi[c] = box[c][0];
      for (const vpImagePoint &p : box[c]) {
        lo[c].set_ij(std::min(lo[c].get_i(), p.get_i()), std::min(lo[c].get_j(), p.get_j()));
        hi[c].set_ij(std::max(hi[c].get_i(), p.get_i()), std::max(hi[c].get_j(), p.get_j()));
      }
    }
    unsigned int compared = 0, different = 0;
    for (unsigned int v = 0; v < height; ++v) {
      for (unsigned int u = 0; u < I.getWidth(); ++u) {
        const unsigned int c = u < width ? 0 : 1, uc = u - c * (width + kGap);
        if (u >= width && u < width + kGap) {
          different += sameColour(I[v][u], vpRGBa(40, 40, 40)) ? 0 : 1;
          ++compared;
          continue;
        }
        const bool overlay = (v + 30.0 >= lo[c].get_i() && v <= hi[c].get_i() + 10.0 && uc + 10.0 >= lo[c].get_j() &&
                              uc <= hi[c].get_j() + 10.0) ||
                             (c == 0 && v < 30 && uc < 200);
        if (!overlay) {
          const unsigned char g = (c == 0 ? Ileft : Iright)[v][uc];
          different += sameColour(I[v][u], vpRGBa(g, g, g)) ? 0 : 1;
          ++compared;
        }
      }
    }
    EXPECT_GT(compared, I.getSize() / 2);
    EXPECT_EQ(different, 0u) << "pixels away from the overlay that are not the images' (of " << compared << ")";
  }
};
#endif

#if defined(VISP_HAVE_X11)
/*
  An X server of its own for the test (Xvfb, 24-bit screen of 1600 x 1200, the first free display number): DISPLAY
  names it while the object lives, for the test's windows and the programs it runs.
*/
class VirtualXServer
{
public:
  VirtualXServer()
  {
    const char *old = std::getenv("DISPLAY");
    m_hadDisplay = old != nullptr;
    m_oldDisplay = old != nullptr ? old : "";
    int fds[2];
    if (pipe(fds) != 0) {
      return;
    }
    m_pid = fork();
    if (m_pid == 0) { // Xvfb writes its display number to fds[1] once it accepts clients
      close(fds[0]);
      if (freopen("/dev/null", "w", stdout) == nullptr || freopen("/dev/null", "w", stderr) == nullptr) {
        _exit(126);
      }
      const std::string fd = std::to_string(fds[1]);
      execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1600x1200x24", "-nolisten", "tcp",
             static_cast<char *>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    char c;
    while (m_pid > 0 && read(fds[0], &c, 1) == 1 && c != '\n') {
      m_number += c;
    }
    close(fds[0]);
    if (!m_number.empty()) {
      setenv("DISPLAY", (":" + m_number).c_str(), 1);
    }
  }
  ~VirtualXServer()
  {
    if (m_pid > 0) {
      kill(m_pid, SIGTERM);
      waitpid(m_pid, nullptr, 0);
    }
    if (m_hadDisplay) {
      setenv("DISPLAY", m_oldDisplay.c_str(), 1);
    } else {
      unsetenv("DISPLAY");
    }
  }
  //! True once the server accepts clients.
  bool isRunning() const { return !m_number.empty(); }

private:
  pid_t m_pid = -1;
  std::string m_number, m_oldDisplay;
  bool m_hadDisplay = false;
};
#define EXPECT_XVFB(server)                                                                                            \
  ASSERT_TRUE(server.isRunning()) << "Xvfb did not start: install Debian's xvfb (scripts/install-deps.sh)";            \
  ASSERT_TRUE(vpStereoServoDisplay::hasDisplay())
#endif
} // namespace

#if defined(VISP_HAVE_APRILTAG)
TEST(StereoServoDisplay, HeadlessPictureShowsTagsFeaturesAndPathsWhereTheyAre)
{
  unsetenv("DISPLAY");
  EXPECT_FALSE(vpStereoServoDisplay::hasDisplay());
  vpStereoServoDisplay display;
  TagScene scene;
  scene.run(display, true); // a window asked for, none possible: headless
  EXPECT_FALSE(display.isOpen());
  scene.check(display.getPicture());
  vpImage<vpRGBa> I;
  EXPECT_THROW(display.getWindowImage(I), vpProjectiveException);
  TemporaryFolder tmp;
  EXPECT_FALSE(display.writePlot(tmp / "plot.png")); // no plot window
  EXPECT_FALSE(vpIoTools::checkFilename(tmp / "plot.png"));
  EXPECT_FALSE(display.getClick()); // does not wait

  // write() without a window: the picture, read back as written (its folder made).
  display.write(tmp / "figures/picture.png");
  vpImageIo::read(I, tmp / "figures/picture.png");
  EXPECT_TRUE(samePicture(I, display.getPicture()));
}

#if defined(VISP_HAVE_X11)
TEST(StereoServoDisplay, WindowUnderXvfbShowsThePictureWithItsOverlay)
{
  VirtualXServer server;
  EXPECT_XVFB(server);
  vpStereoServoDisplay display;
  TagScene scene;
  scene.run(display, true);
  ASSERT_TRUE(display.isOpen());
  vpImage<vpRGBa> I;
  display.getWindowImage(I); // what the X server shows
  scene.check(I);
  EXPECT_TRUE(samePicture(I, display.getPicture()));
  EXPECT_FALSE(display.getClick(false)); // nobody clicked

  TemporaryFolder tmp;
  EXPECT_TRUE(
      display.writePlot(tmp / "plot.png")); // the plot window opened at the first plot(): two graphs under the picture
  vpImage<vpRGBa> P;
  vpImageIo::read(P, tmp / "plot.png");
  EXPECT_EQ(P.getWidth(), I.getWidth());
  EXPECT_EQ(P.getHeight(), 500u);
}
#endif
#endif

TEST(StereoServoDisplay, BadInputIsRefusedAndChangesNothing)
{
  vpStereoServoDisplay display;
  vpImage<unsigned char> I(48, 64, 100), small(47, 64, 100);
  EXPECT_THROW(display.display(I, I), vpProjectiveException); // before init()
  EXPECT_THROW(display.init(0, 48, false), vpProjectiveException);
  display.init(64, 48, false);
  EXPECT_THROW(display.display(I, small), vpProjectiveException);
  display.display(I, I);
  display.flush();
  const vpImage<vpRGBa> before = display.getPicture();
  const vpImagePoint p(10, 10), nan(std::nan(""), 3.0);
  EXPECT_THROW(display.displayTags({0, 1}, {p, p}, {p}), vpProjectiveException);
  EXPECT_THROW(display.displayTags({0}, {p, p}, {p, p}), vpProjectiveException);
  EXPECT_THROW(display.displayTags({0, -1}, {p, p}, {p, p}), vpProjectiveException);
  EXPECT_THROW(display.displayTags({0, 1}, {p, p}, {p, nan}), vpProjectiveException);
  EXPECT_THROW(display.displayMarkers({p}, {}), vpProjectiveException);
  EXPECT_THROW(display.displayMarkers({nan}, {p}), vpProjectiveException);
  display.flush();
  EXPECT_TRUE(samePicture(display.getPicture(), before));
  vpFeatureStereoPoint s, s_star; // features are finite: vpFeatureStereoPoint::buildFrom() refuses NaN
  s_star.buildFrom(p, p);
  display.displayFeature(0, s, s_star, false); // not seen: s is not drawn, s* is
  display.flush();
  EXPECT_FALSE(samePicture(display.getPicture(), before));
  EXPECT_TRUE(colourAt(display.getPicture(), p, kRed, "s*"));
  EXPECT_TRUE(colourAt(display.getPicture(), vpImagePoint(0, 0), vpRGBa(100, 100, 100), "s of a feature not seen"));

  EXPECT_THROW(display.plot(vpColVector(5, 1.0), vpColVector(6, 0.0)), vpProjectiveException);
  EXPECT_THROW(display.plot(vpColVector(), vpColVector(6, 0.0)), vpProjectiveException);
  vpColVector e(8, 1.0);
  e[3] = std::nan("");
  EXPECT_THROW(display.plot(e, vpColVector(6, 0.0)), vpProjectiveException);
  display.plot(vpColVector(8, 1.0), vpColVector(6, 0.0));
  EXPECT_THROW(display.plot(vpColVector(8, 1.0), vpColVector(5, 0.0)), vpProjectiveException);
  EXPECT_THROW(display.plot(vpColVector(12, 1.0), vpColVector(6, 0.0)), vpProjectiveException);
  display.plot(vpColVector(8, 2.0), vpColVector(6, 0.0));
  EXPECT_THROW(display.write("/proc/no-folder-here/picture.png"), vpProjectiveException);
}

#if defined(VISP_PROJECTIVE_TUTORIAL_APRILTAG) && defined(VISP_HAVE_X11) && defined(VISP_HAVE_APRILTAG)
/*
  The AprilTag tutorial run as a user runs it, with its display on (an Xvfb of its own) and -c: it exits 0 by itself,
  and the window it saved at its end shows, at each s* it printed, in both images, the converged feature (green
  centre) inside the desired feature's cross (red tips 6 and 7 px away).
*/
TEST(StereoServoDisplay, AprilTagTutorialRunsWithItsDisplayOnUnderXvfb)
{
  VirtualXServer server;
  EXPECT_XVFB(server);
  TemporaryFolder tmp;
  const std::string command = std::string("'") + VISP_PROJECTIVE_TUTORIAL_APRILTAG + "' -c --output '" + tmp.path() +
                              "' > '" + (tmp / "out.txt") + "' 2> '" + (tmp / "err.txt") + "'";
  const int raw = std::system(command.c_str());
  const std::string out = readText(tmp / "out.txt");
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << out << readText(tmp / "err.txt");

  const std::string number = "([-0-9.e+]+)";
  const std::regex line(R"(s\*\[\d\] \(i, j\): left )" + number + ", " + number + ", right " + number + ", " + number);
  std::vector<vpImagePoint> desired[2];
  for (std::sregex_iterator m(out.begin(), out.end(), line), end; m != end; ++m) {
    desired[0].push_back(vpImagePoint(std::stod((*m)[1]), std::stod((*m)[2])));
    desired[1].push_back(vpImagePoint(std::stod((*m)[3]), std::stod((*m)[4])));
  }
  ASSERT_EQ(desired[0].size(), 4u) << out;
  vpImage<vpRGBa> I, P;
  vpImageIo::read(I, tmp / "stereo-end.png");
  vpImageIo::read(P, tmp / "plot.png");
  const unsigned int width = (I.getWidth() - kGap) / 2;
  ASSERT_EQ(width, 640u);
  ASSERT_EQ(I.getHeight(), 480u);
  EXPECT_GT(P.getSize(), 0u);
  for (unsigned int c = 0; c < 2; ++c) {
    for (const vpImagePoint &p : desired[c]) {
      const vpImagePoint at = drawn(p, c, width);
      EXPECT_TRUE(colourAt(I, at, kGreen, "converged feature"));
      for (const vpImagePoint &tip : {vpImagePoint(0, 7), vpImagePoint(0, -7), vpImagePoint(7, 0), vpImagePoint(-7, 0),
                                      vpImagePoint(0, 6), vpImagePoint(-6, 0)}) {
        EXPECT_TRUE(colourAt(I, at + tip, kRed, "tip of the desired feature's cross"));
      }
    }
  }
}
#endif
