#pragma once
// Symbol visibility of the public API: the shared library (lumaslam::lumaslam) is built with
// hidden visibility, so that only what is marked here is exported.
#if defined(_WIN32)
#define LUMASLAM_API
#else
#define LUMASLAM_API __attribute__((visibility("default")))
#endif
