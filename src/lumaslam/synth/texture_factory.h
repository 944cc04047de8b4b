#pragma once
// Procedural, multi-scale surface textures rich enough for ORB at 0.5-5 m: value noise at
// several scales, blobs, posters (checker, stripes, rings, text, user images), lines, planks,
// panels and book rows. Deterministic for a given Rng state.
#include <vector>

#include <opencv2/core.hpp>

#include "lumaslam/synth/random.h"

namespace lumaslam::synth {

enum class SurfaceStyle { Wall, Floor, Ceiling, Crate, Shelf, Table };

// A CV_8UC3 BGR image of `size_m` metres at `texel_size_m` per texel. `posters` (may be empty)
// are user images pasted as posters on walls and crates.
cv::Mat makeSurfaceTexture(cv::Size2f size_m, float texel_size_m, SurfaceStyle style, Rng& rng,
                           const std::vector<cv::Mat>& posters);

// Clothing, skin and hair for a walker billboard of `width_m` x `height_m` (head at the top).
cv::Mat makeWalkerTexture(float width_m, float height_m, float texel_size_m, Rng& rng);

}  // namespace lumaslam::synth
