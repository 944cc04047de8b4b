#pragma once
// Our own contrast-limited adaptive histogram equalisation (paper Eq. 9-10, 14-19), laid out
// like cv::CLAHE so that with the same grid and limit the two agree to +-1 gray level:
// per-tile 256-bin histograms on the image padded (BORDER_REFLECT_101) to a multiple of the
// grid, clipping with uniform redistribution, CDF lookup tables and bilinear interpolation
// between the four nearest tile centres. Unlike cv::CLAHE, every tile may have its own limit.
// The stages are public so the Enhancer can fold brightness compensation into the tables.
#include <opencv2/core.hpp>

namespace lumaslam::enhance {

class Clahe {
 public:
  // Throws Error unless 1 <= tiles <= 64 in both directions.
  Clahe(int tiles_x, int tiles_y);

  // One clip limit for every tile, in OpenCV's normalised units (absolute clip count =
  // limit * tile_pixels / 256, at least 1); limit <= 0 disables clipping.
  cv::Mat apply(const cv::Mat& gray, double limit) const;
  // tile_limits: CV_64FC1, tiles_y x tiles_x, one normalised limit per tile.
  cv::Mat apply(const cv::Mat& gray, const cv::Mat& tile_limits) const;

  // The image the tile histograms are taken from (the input, padded when its size is not a
  // multiple of the grid) and the tile size in it.
  struct Tiling {
    cv::Mat padded;
    cv::Size tile;
  };
  Tiling tiling(const cv::Mat& gray) const;

  // Eq. 9: CV_32SC1, one 256-bin row per tile (row ty * tiles_x + tx).
  cv::Mat tileHistograms(const Tiling& tiling) const;
  // Eq. 10, 14-15 and the CDF: one 8-bit table per tile (CV_8UC1, tiles x 256) from the
  // histograms of tiles of `tile_pixels` pixels. `histograms` is clipped in place.
  cv::Mat lookupTables(cv::Mat& histograms, const cv::Mat& tile_limits, int tile_pixels) const;
  // Eq. 16-19: maps `gray` through the per-tile tables, `tile` being the tile size of the
  // tiling the tables came from. With one tile this is a plain table lookup.
  void interpolate(const cv::Mat& gray, const cv::Mat& luts, cv::Size tile, cv::Mat& out) const;

  int tilesX() const { return tiles_x_; }
  int tilesY() const { return tiles_y_; }

 private:
  int tiles_x_;
  int tiles_y_;
};

// Adds the 256-bin histogram of an 8-bit single-channel image (or ROI) to `hist`.
void accumulateHistogram(const cv::Mat& gray, int* hist);

}  // namespace lumaslam::enhance
