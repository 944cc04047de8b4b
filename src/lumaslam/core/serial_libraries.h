#pragma once
// ThreadSanitizer builds only (LUMASLAM_SERIAL_LIBRARIES, set by -DLUMASLAM_SANITIZE=thread):
// OpenCV and TBB are not built with TSan, so the synchronisation inside their worker pools is
// invisible to it and every buffer a parallel loop touches is reported as a race. While an
// object of this class lives, cv::parallel_for_ and tbb::parallel_for run inline on the
// calling thread, so TSan sees only our own std::threads (tracking and the core::Stage threads
// of local mapping, loop closing, global BA and detection; the core::startSideJob jobs).
// Release builds never create one.
// OpenMP (SuiteSparse CHOLMOD under Ceres) is the third pool: it is capped from outside with
// OMP_THREAD_LIMIT=1, which the TSan tests set (tests/CMakeLists.txt, make test-tsan).
#include <tbb/global_control.h>
#include <opencv2/core/utility.hpp>

namespace lumaslam::core {

class SerialLibraries {
 public:
  SerialLibraries() { cv::setNumThreads(1); }

 private:
  tbb::global_control tbb_limit_{tbb::global_control::max_allowed_parallelism, 1};
};

}  // namespace lumaslam::core
