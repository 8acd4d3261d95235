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

#include <visp3/projective/vpStereoGrabberSource.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>

#if defined(VISP_HAVE_MODULE_SENSOR) && defined(VISP_HAVE_V4L2)
#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <visp3/sensor/vpV4l2Grabber.h>
#endif

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpStereoGrabberSource");

#if defined(VISP_HAVE_MODULE_SENSOR) && defined(VISP_HAVE_V4L2)
//! The first line of the text file \e path, empty if it cannot be read.
std::string firstLine(const std::string &path)
{
  std::ifstream file(path.c_str());
  std::string line;
  std::getline(file, line);
  return line;
}

/*!
  The serial number of the USB camera behind the V4L2 device \e device, from sysfs: the device node's
  /sys/class/video4linux/videoN/device is the USB interface, whose parent holds the USB device's \c serial (its
  iSerial string); empty if there is none (not a USB camera, no serial number, no sysfs).
*/
std::string usbSerial(const std::string &device)
{
  std::error_code error;
  const std::filesystem::path node = std::filesystem::canonical(device, error);
  if (error) {
    return std::string();
  }
  const std::filesystem::path interface =
      std::filesystem::canonical("/sys/class/video4linux" / node.filename() / "device", error);
  return error ? std::string() : firstLine((interface.parent_path() / "serial").string());
}
#endif

#if defined(VISP_HAVE_MODULE_SENSOR) && defined(VISP_HAVE_V4L2)
/*!
  A V4L2 grabber opened on \e device, or the error that names it; \e identity receives the camera's identity (the
  device, V4L2's card and bus_info, the USB serial number).
*/
std::unique_ptr<vpFrameGrabber> openV4l2(const std::string &device, unsigned int scale, const char *side,
                                         vpStereoImageSource::vpCameraIdentity &identity)
{
  if (device.empty() || device.size() >= FILENAME_MAX) {
    fail(vpProjectiveException::invalidValueError, at("vpStereoGrabberSource()"),
         std::string("the ") + side + " camera's device name is empty or too long; give a path such as /dev/video0");
  }
  std::error_code error;
  if (!std::filesystem::exists(device, error)) {
    fail(vpProjectiveException::fileError, at("vpStereoGrabberSource()"),
         std::string("cannot open the ") + side + " camera '" + device +
             "': no such device; check that the camera is plugged in and its name (ls /dev/video*)");
  }
  // A path that is no video capture device (a file, /dev/null) is named here: vpV4l2Grabber and libv4l2 would print
  // their own messages on the standard output and error before failing.
  bool capture = false;
  const int fd = ::open(device.c_str(), O_RDWR | O_NONBLOCK);
  if (fd >= 0) {
    v4l2_capability cap{};
    capture = ::ioctl(fd, VIDIOC_QUERYCAP, &cap) == 0 &&
              (((cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities) &
               (V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_VIDEO_CAPTURE_MPLANE)) != 0;
    ::close(fd);
    identity.device = device;
    identity.name = std::string(reinterpret_cast<const char *>(cap.card),
                                strnlen(reinterpret_cast<const char *>(cap.card), sizeof(cap.card)));
    identity.bus = std::string(reinterpret_cast<const char *>(cap.bus_info),
                               strnlen(reinterpret_cast<const char *>(cap.bus_info), sizeof(cap.bus_info)));
    identity.serial = usbSerial(device);
  }
  if (!capture) {
    fail(vpProjectiveException::fileError, at("vpStereoGrabberSource()"),
         std::string("cannot open the ") + side + " camera '" + device + "' (" +
             (fd < 0 ? std::string("cannot open it for reading and writing") : "not a video capture device") +
             "); check the device's name (v4l2-ctl --list-devices) and that you may read it (group video)");
  }
  std::unique_ptr<vpV4l2Grabber> g(new vpV4l2Grabber());
  g->setDevice(device);
  g->setScale(scale);
  vpImage<unsigned char> I;
  try {
    g->open(I);
  } catch (const vpException &e) {
    fail(vpProjectiveException::fileError, at("vpStereoGrabberSource()"),
         std::string("cannot open the ") + side + " camera '" + device + "' (" + e.getStringMessage() +
             "); check that the camera is plugged in, that the device exists (ls /dev/video*) and that you may read "
             "it (group video)");
  }
  return std::unique_ptr<vpFrameGrabber>(g.release());
}
#endif
} // namespace

vpStereoGrabberSource::vpStereoGrabberSource(const std::string &leftDevice, const std::string &rightDevice,
                                             unsigned int scale)
    : m_ownedLeft(), m_ownedRight(), m_left(nullptr), m_right(nullptr), m_leftName(leftDevice),
      m_rightName(rightDevice), m_stamps{0.0, 0.0}, m_stamped(false)
{
#if defined(VISP_HAVE_MODULE_SENSOR) && defined(VISP_HAVE_V4L2)
  if (scale == 0) {
    fail(vpProjectiveException::invalidValueError, at("vpStereoGrabberSource()"),
         "the subsampling scale must be 1 (full resolution) or more");
  }
  m_ownedLeft = openV4l2(leftDevice, scale, "left", m_identities[0]);
  m_ownedRight = openV4l2(rightDevice, scale, "right", m_identities[1]);
  m_left = m_ownedLeft.get();
  m_right = m_ownedRight.get();
#else
  (void)scale;
  fail(vpProjectiveException::fileError, at("vpStereoGrabberSource()"),
       "cannot open '" + leftDevice + "' and '" + rightDevice +
           "': this ViSP was built without V4L2; open the cameras with another ViSP grabber and pass them to "
           "vpStereoGrabberSource(vpFrameGrabber &, vpFrameGrabber &)");
#endif
}

vpStereoGrabberSource::vpStereoGrabberSource(vpFrameGrabber &left, vpFrameGrabber &right)
    : m_ownedLeft(), m_ownedRight(), m_left(&left), m_right(&right), m_leftName("left grabber"),
      m_rightName("right grabber"), m_stamps{0.0, 0.0}, m_stamped(false)
{
  if (left.getWidth() == 0 || left.getHeight() == 0 || right.getWidth() == 0 || right.getHeight() == 0) {
    fail(vpProjectiveException::notInitializedError, at("vpStereoGrabberSource()"),
         "a grabber has an image size of 0: open() both grabbers before passing them");
  }
}

vpStereoGrabberSource::~vpStereoGrabberSource() {}

bool vpStereoGrabberSource::getCameraIdentities(vpCameraIdentity &left, vpCameraIdentity &right) const
{
  if (m_ownedLeft == nullptr) {
    return false; // grabbers opened by the caller: their identities are the caller's to record
  }
  left = m_identities[0];
  right = m_identities[1];
  return true;
}

bool vpStereoGrabberSource::acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright)
{
  m_stamped = false;
  bool stamped = true;
  for (int camera = 0; camera < 2; ++camera) {
    vpFrameGrabber *grabber = camera == 0 ? m_left : m_right;
    vpImage<unsigned char> &I = camera == 0 ? Ileft : Iright;
    try {
#if defined(VISP_HAVE_MODULE_SENSOR) && defined(VISP_HAVE_V4L2)
      if (vpV4l2Grabber *v4l2 = dynamic_cast<vpV4l2Grabber *>(grabber)) {
        timeval stamp{};
        v4l2->acquire(I, stamp);
        const double now = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
        m_stamps[camera] = static_cast<double>(stamp.tv_sec) + 1e-6 * static_cast<double>(stamp.tv_usec);
        // A driver stamping on the wall clock gives an instant decades away from the monotonic one: no stamp then.
        stamped = stamped && m_stamps[camera] <= now + 1e-3 && m_stamps[camera] > now - 10.0;
        continue;
      }
#endif
      grabber->acquire(I);
      stamped = false;
    } catch (const vpException &e) {
      fail(vpProjectiveException::fileError, at("acquire()"),
           "the " + std::string(camera == 0 ? "left" : "right") + " camera '" +
               (camera == 0 ? m_leftName : m_rightName) + "' failed to give an image (" + e.getStringMessage() +
               "); check its cable and that no other program uses it");
    }
  }
  m_stamped = stamped;
  return true;
}

bool vpStereoGrabberSource::getTimestamps(double &left, double &right) const
{
  if (m_stamped) {
    left = m_stamps[0];
    right = m_stamps[1];
  }
  return m_stamped;
}
