#include "lumaslam/synth/texture_factory.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <opencv2/imgproc.hpp>

namespace lumaslam::synth {

namespace {

// HSV (h in degrees, s and v in 0..1) to an 8-bit BGR colour.
cv::Scalar hsvColor(double h, double s, double v) {
  const double c = v * s;
  const double hp = std::fmod(h, 360.0) / 60.0;
  const double x = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0));
  double r = 0, g = 0, b = 0;
  if (hp < 1) {
    r = c, g = x;
  } else if (hp < 2) {
    r = x, g = c;
  } else if (hp < 3) {
    g = c, b = x;
  } else if (hp < 4) {
    g = x, b = c;
  } else if (hp < 5) {
    r = x, b = c;
  } else {
    r = c, b = x;
  }
  const double m = v - c;
  return {255.0 * (b + m), 255.0 * (g + m), 255.0 * (r + m)};
}

cv::Scalar randomColor(Rng& rng, double s_lo, double s_hi, double v_lo, double v_hi) {
  return hsvColor(rng.uniform(0, 360), rng.uniform(s_lo, s_hi), rng.uniform(v_lo, v_hi));
}

class Painter {
 public:
  Painter(cv::Size2f size_m, float texel_size_m, Rng& rng)
      : texel_(texel_size_m),
        rng_(rng),
        image_(std::max(8, static_cast<int>(std::ceil(size_m.height / texel_size_m))),
               std::max(8, static_cast<int>(std::ceil(size_m.width / texel_size_m))), CV_8UC3) {}

  cv::Mat& image() { return image_; }
  Rng& rng() { return rng_; }
  int px(double metres) const {
    return std::max(1, static_cast<int>(std::lround(metres / texel_)));
  }
  double widthM() const { return image_.cols * texel_; }
  double heightM() const { return image_.rows * texel_; }

  // Base colour modulated by value noise at the given feature sizes (metres).
  void fillNoisy(const cv::Scalar& base, const std::vector<std::pair<double, double>>& octaves) {
    cv::Mat shade(image_.size(), CV_32F, cv::Scalar(1.0f));
    for (const auto& [scale_m, amplitude] : octaves) {
      const int gw = std::max(2, static_cast<int>(widthM() / scale_m) + 2);
      const int gh = std::max(2, static_cast<int>(heightM() / scale_m) + 2);
      cv::Mat grid(gh, gw, CV_32F);
      for (int y = 0; y < gh; ++y)
        for (int x = 0; x < gw; ++x)
          grid.at<float>(y, x) = static_cast<float>(rng_.uniform() - 0.5);
      cv::Mat noise;
      cv::resize(grid, noise, image_.size(), 0, 0, cv::INTER_CUBIC);
      shade += noise * (2.0 * amplitude);
    }
    std::vector<cv::Mat> channels(3);
    for (int c = 0; c < 3; ++c) channels[static_cast<size_t>(c)] = shade * base[c];
    cv::Mat merged;
    cv::merge(channels, merged);
    merged.convertTo(image_, CV_8UC3);
  }

  void blobs(int count, double r_lo_m, double r_hi_m, double alpha_v) {
    for (int i = 0; i < count; ++i) {
      const cv::Point c(rng_.uniformInt(0, image_.cols - 1), rng_.uniformInt(0, image_.rows - 1));
      const cv::Size axes(px(rng_.uniform(r_lo_m, r_hi_m)), px(rng_.uniform(r_lo_m, r_hi_m)));
      cv::ellipse(image_, c, axes, rng_.uniform(0, 180), 0, 360,
                  randomColor(rng_, 0.1, 0.8, alpha_v * 0.3, alpha_v), cv::FILLED, cv::LINE_AA);
    }
  }

  void lines(int count, double length_m, int max_thickness) {
    for (int i = 0; i < count; ++i) {
      const cv::Point a(rng_.uniformInt(0, image_.cols - 1), rng_.uniformInt(0, image_.rows - 1));
      const double angle = rng_.uniform(0, 2 * CV_PI);
      const double len = px(rng_.uniform(0.3, 1.0) * length_m);
      const cv::Point b(a.x + static_cast<int>(len * std::cos(angle)),
                        a.y + static_cast<int>(len * std::sin(angle)));
      cv::line(image_, a, b, randomColor(rng_, 0.0, 0.6, 0.05, 0.5),
               rng_.uniformInt(1, max_thickness), cv::LINE_AA);
    }
  }

  // A framed rectangle with one of several rich patterns inside.
  void poster(const cv::Rect& rect, const std::vector<cv::Mat>& user_images) {
    const cv::Rect r = rect & cv::Rect(0, 0, image_.cols, image_.rows);
    if (r.width < 8 || r.height < 8) return;
    cv::Mat roi = image_(r);
    const cv::Scalar c1 = randomColor(rng_, 0.2, 0.9, 0.5, 0.95);
    const cv::Scalar c2 = randomColor(rng_, 0.2, 0.9, 0.05, 0.45);
    const int kind = rng_.uniformInt(0, user_images.empty() ? 4 : 5);
    roi.setTo(c1);
    if (kind == 0) {  // checker
      const int cell = px(rng_.uniform(0.02, 0.08));
      for (int y = 0; y < r.height; y += cell)
        for (int x = ((y / cell) % 2) * cell; x < r.width; x += 2 * cell)
          cv::rectangle(roi, cv::Rect(x, y, cell, cell), c2, cv::FILLED);
    } else if (kind == 1) {  // stripes at an angle
      const double angle = rng_.uniform(0, CV_PI);
      const int spacing = px(rng_.uniform(0.02, 0.07));
      const int diag = r.width + r.height;
      for (int s = -diag; s < diag; s += spacing) {
        const cv::Point p(r.width / 2 + static_cast<int>(s * std::cos(angle)),
                          r.height / 2 + static_cast<int>(s * std::sin(angle)));
        const cv::Point d(static_cast<int>(-diag * std::sin(angle)),
                          static_cast<int>(diag * std::cos(angle)));
        cv::line(roi, p - d, p + d, c2, std::max(1, spacing / 3), cv::LINE_AA);
      }
    } else if (kind == 2) {  // rings and dots
      const int rings = rng_.uniformInt(3, 8);
      const cv::Point centre(r.width / 2, r.height / 2);
      for (int i = rings; i > 0; --i)
        cv::circle(roi, centre, std::min(r.width, r.height) * i / (2 * rings),
                   i % 2 ? c2 : randomColor(rng_, 0.3, 1.0, 0.4, 1.0), cv::FILLED, cv::LINE_AA);
    } else if (kind == 3) {  // text page
      Painter::textInto(roi, rng_, px(rng_.uniform(0.02, 0.05)), c2);
    } else if (kind == 4) {  // abstract shapes
      for (int i = 0; i < 25; ++i) {
        const cv::Point c(rng_.uniformInt(0, r.width - 1), rng_.uniformInt(0, r.height - 1));
        const int rad = rng_.uniformInt(2, std::max(3, std::min(r.width, r.height) / 4));
        if (rng_.chance(0.5))
          cv::circle(roi, c, rad, randomColor(rng_, 0.3, 1.0, 0.1, 1.0), cv::FILLED, cv::LINE_AA);
        else
          cv::rectangle(roi, cv::Rect(c.x, c.y, rad, rad * 2),
                        randomColor(rng_, 0.3, 1.0, 0.1, 1.0), cv::FILLED);
      }
    } else {  // a user image
      const cv::Mat& src = user_images[static_cast<size_t>(
          rng_.uniformInt(0, static_cast<int>(user_images.size()) - 1))];
      cv::resize(src, roi, roi.size(), 0, 0, cv::INTER_AREA);
    }
    cv::rectangle(image_, r, c2 * 0.5, std::max(1, px(0.01)));
  }

  static void textInto(cv::Mat& roi, Rng& rng, int letter_px, const cv::Scalar& color) {
    const double scale = letter_px / 22.0;
    const int thickness = std::max(1, static_cast<int>(scale * 2));
    const int step = std::max(2, static_cast<int>(letter_px * 1.6));
    for (int y = step; y < roi.rows; y += step) {
      std::string word;
      const int letters = rng.uniformInt(3, 14);
      for (int i = 0; i < letters; ++i)
        word += rng.chance(0.15) ? ' ' : static_cast<char>('A' + rng.uniformInt(0, 25));
      cv::putText(roi, word, {letter_px / 3, y}, cv::FONT_HERSHEY_SIMPLEX, scale, color, thickness,
                  cv::LINE_AA);
    }
  }

  void randomPosters(int count, double lo_m, double hi_m, const std::vector<cv::Mat>& user_images) {
    for (int i = 0; i < count; ++i) {
      const int w = px(rng_.uniform(lo_m, hi_m));
      const int h = px(rng_.uniform(lo_m, hi_m));
      const cv::Rect rect(rng_.uniformInt(0, std::max(0, image_.cols - w)),
                          rng_.uniformInt(0, std::max(0, image_.rows - h)), w, h);
      poster(rect, user_images);
    }
  }

 private:
  float texel_;
  Rng& rng_;
  cv::Mat image_;
};

void paintFloor(Painter& p) {
  const cv::Scalar wood = hsvColor(p.rng().uniform(20, 40), p.rng().uniform(0.3, 0.6), 0.6);
  p.fillNoisy(wood, {{0.6, 0.12}, {0.12, 0.08}, {0.02, 0.06}});
  const int plank = p.px(p.rng().uniform(0.12, 0.2));
  cv::Mat& img = p.image();
  for (int y = 0; y < img.rows; y += plank) {
    const cv::Rect band(0, y, img.cols, std::min(plank, img.rows - y));
    img(band) *= p.rng().uniform(0.75, 1.15);
    cv::line(img, {0, y}, {img.cols, y}, cv::Scalar(30, 40, 50), 1, cv::LINE_AA);
    for (int x = p.rng().uniformInt(0, p.px(1.0)); x < img.cols;
         x += p.px(p.rng().uniform(0.8, 1.6)))
      cv::line(img, {x, y}, {x, y + plank}, cv::Scalar(30, 40, 50), 1, cv::LINE_AA);
  }
  p.blobs(static_cast<int>(p.widthM() * p.heightM() * 6), 0.01, 0.06, 0.6);
  p.lines(static_cast<int>(p.widthM() * p.heightM()), 0.5, 2);
}

void paintCeiling(Painter& p) {
  p.fillNoisy(hsvColor(p.rng().uniform(0, 60), 0.05, 0.85), {{0.5, 0.05}, {0.05, 0.05}});
  const int panel = p.px(0.6);
  cv::Mat& img = p.image();
  for (int y = 0; y < img.rows; y += panel)
    cv::line(img, {0, y}, {img.cols, y}, cv::Scalar(90, 90, 90), 2);
  for (int x = 0; x < img.cols; x += panel)
    cv::line(img, {x, 0}, {x, img.rows}, cv::Scalar(90, 90, 90), 2);
  p.blobs(static_cast<int>(p.widthM() * p.heightM() * 3), 0.01, 0.04, 0.5);
}

void paintWall(Painter& p, const std::vector<cv::Mat>& user_images) {
  p.fillNoisy(randomColor(p.rng(), 0.05, 0.35, 0.6, 0.9),
              {{0.8, 0.08}, {0.15, 0.08}, {0.03, 0.06}});
  const double area = p.widthM() * p.heightM();
  p.blobs(static_cast<int>(area * 8), 0.01, 0.05, 0.7);
  p.lines(static_cast<int>(area * 1.5), 0.8, 3);
  p.randomPosters(std::max(2, static_cast<int>(area / 1.5)), 0.25, 0.9, user_images);
  // Skirting board along the bottom edge (v grows downwards).
  cv::Mat& img = p.image();
  const int skirting = p.px(0.1);
  img(cv::Rect(0, img.rows - skirting, img.cols, skirting))
      .setTo(randomColor(p.rng(), 0, 0.3, 0.2, 0.5));
}

void paintCrate(Painter& p, const std::vector<cv::Mat>& user_images) {
  p.fillNoisy(randomColor(p.rng(), 0.2, 0.7, 0.4, 0.85), {{0.3, 0.1}, {0.05, 0.08}, {0.01, 0.05}});
  const double area = p.widthM() * p.heightM();
  p.blobs(static_cast<int>(area * 30) + 3, 0.01, 0.04, 0.9);
  p.randomPosters(1 + static_cast<int>(area * 3), 0.1,
                  std::min(0.4, 0.8 * std::min(p.widthM(), p.heightM())) + 0.05, user_images);
  p.lines(static_cast<int>(area * 6) + 1, 0.4, 2);
  cv::Mat& img = p.image();
  Painter::textInto(img, p.rng(), p.px(0.03), randomColor(p.rng(), 0, 0.5, 0.0, 0.3));
}

void paintShelf(Painter& p) {
  p.fillNoisy(hsvColor(p.rng().uniform(20, 40), 0.4, 0.5), {{0.2, 0.1}, {0.02, 0.05}});
  cv::Mat& img = p.image();
  const int board = p.px(0.03);
  const int row_height = p.px(0.35);
  for (int top = board; top + row_height < img.rows; top += row_height + board) {
    int x = board;
    while (x < img.cols - board) {
      const int w = p.px(p.rng().uniform(0.02, 0.07));
      const int h = static_cast<int>(row_height * p.rng().uniform(0.6, 0.98));
      const cv::Rect book(x, top + row_height - h, std::min(w, img.cols - board - x), h);
      img(book).setTo(randomColor(p.rng(), 0.3, 0.9, 0.2, 0.9));
      if (p.rng().chance(0.5))
        cv::line(img, {book.x, book.y + h / 4}, {book.x + book.width, book.y + h / 4},
                 cv::Scalar(220, 220, 220), 1);
      x += book.width + (p.rng().chance(0.1) ? p.px(0.08) : 0);
    }
  }
}

void paintTable(Painter& p) {
  p.fillNoisy(randomColor(p.rng(), 0.1, 0.5, 0.3, 0.8), {{0.4, 0.1}, {0.05, 0.08}, {0.01, 0.04}});
  p.blobs(static_cast<int>(p.widthM() * p.heightM() * 40) + 2, 0.01, 0.05, 0.9);
  p.lines(static_cast<int>(p.widthM() * p.heightM() * 10) + 1, 0.3, 2);
}

}  // namespace

cv::Mat makeSurfaceTexture(cv::Size2f size_m, float texel_size_m, SurfaceStyle style, Rng& rng,
                           const std::vector<cv::Mat>& posters) {
  Painter painter(size_m, texel_size_m, rng);
  switch (style) {
    case SurfaceStyle::Wall:
      paintWall(painter, posters);
      break;
    case SurfaceStyle::Floor:
      paintFloor(painter);
      break;
    case SurfaceStyle::Ceiling:
      paintCeiling(painter);
      break;
    case SurfaceStyle::Crate:
      paintCrate(painter, posters);
      break;
    case SurfaceStyle::Shelf:
      paintShelf(painter);
      break;
    case SurfaceStyle::Table:
      paintTable(painter);
      break;
  }
  return painter.image();
}

cv::Mat makeWalkerTexture(float width_m, float height_m, float texel_size_m, Rng& rng) {
  Painter p({width_m, height_m}, texel_size_m, rng);
  cv::Mat& img = p.image();
  const auto rowAt = [&](double height_from_floor) {
    return std::clamp(static_cast<int>((height_m - height_from_floor) / texel_size_m), 0, img.rows);
  };
  // Trousers below the hips, shirt up to the neck, skin and hair above.
  p.fillNoisy(randomColor(rng, 0.2, 0.7, 0.15, 0.5), {{0.1, 0.1}, {0.02, 0.08}});
  const cv::Rect shirt(0, rowAt(1.5 / 1.75 * height_m), img.cols,
                       rowAt(0.9 / 1.75 * height_m) - rowAt(1.5 / 1.75 * height_m));
  cv::Mat top = img(shirt);
  top.setTo(randomColor(rng, 0.3, 0.9, 0.4, 0.95));
  const cv::Scalar pattern = randomColor(rng, 0.3, 1.0, 0.1, 0.9);
  const int kind = rng.uniformInt(0, 2);
  const int cell = p.px(rng.uniform(0.03, 0.07));
  for (int y = 0; y < top.rows; y += cell) {
    if (kind == 0) cv::line(top, {0, y}, {top.cols, y}, pattern, std::max(1, cell / 3));
    for (int x = (y / cell % 2) * cell; kind == 1 && x < top.cols; x += 2 * cell)
      cv::rectangle(top, cv::Rect(x, y, cell, cell), pattern, cv::FILLED);
  }
  if (kind == 2) Painter::textInto(top, rng, p.px(0.05), pattern);
  p.blobs(40, 0.005, 0.02, 0.9);
  const cv::Rect head(0, 0, img.cols, rowAt(1.5 / 1.75 * height_m));
  img(head).setTo(hsvColor(rng.uniform(15, 35), rng.uniform(0.3, 0.6), rng.uniform(0.4, 0.9)));
  img(cv::Rect(0, 0, img.cols, rowAt(1.66 / 1.75 * height_m)))
      .setTo(randomColor(rng, 0.2, 0.6, 0.05, 0.35));
  return img;
}

}  // namespace lumaslam::synth
