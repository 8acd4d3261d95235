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
  \file vpProjectiveConfig.h
  \brief The ViSP configuration every header of the plugin starts from, and ViSP's namespace macros on every ViSP
  version.

  ViSP 3.7 can be built with ENABLE_VISP_NAMESPACE=ON, which puts every ViSP class in the namespace \c visp; its
  vpConfig.h then defines BEGIN_VISP_NAMESPACE as <tt>namespace visp {</tt> and END_VISP_NAMESPACE as <tt>}</tt>
  (both empty otherwise). The plugin's public headers wrap their declarations in these macros, as ViSP's own headers
  do, so that its classes live beside ViSP's in either case. ViSP 3.5 and 3.6 define neither macro: they are defined
  empty here, and the plugin's classes stay in the global namespace with ViSP's.

  Programs written against the plugin follow ViSP's own pattern, which compiles on every version:
  \code
  #include <visp3/projective/vpServoProjective.h>
  #ifdef ENABLE_VISP_NAMESPACE
  using namespace VISP_NAMESPACE_NAME;
  #endif
  \endcode
*/

#ifndef _vpProjectiveConfig_h_
#define _vpProjectiveConfig_h_

#include <visp3/core/vpConfig.h>

#ifndef BEGIN_VISP_NAMESPACE
//! ViSP before 3.7 has no namespace: the plugin's declarations are global, as ViSP's.
#define BEGIN_VISP_NAMESPACE
//! ViSP before 3.7 has no namespace: closes nothing.
#define END_VISP_NAMESPACE
#endif

#endif
