// Experiment plans (`lumaslam experiment PLAN.yaml`).
#include <cstddef>
#include <cstdint>

#include "experiment_plan.h"
#include "input_file.h"
#include "rejected_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lumaslam::fuzz::InputFile input("plan.yaml", data, size);
  lumaslam::fuzz::parseOrReject([&] { lumaslam::cli::readPlan(input.path()); });
  return 0;
}
