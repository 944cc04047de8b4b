#include "lumaslam/loop/bow_vector.h"

#include <cmath>

namespace lumaslam::loop {

namespace {

// Calls visit(weight_a, weight_b) for every word the two sorted vectors share.
template <typename Visit>
void forSharedWords(const BowVector& a, const BowVector& b, Visit&& visit) {
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->word < ib->word) {
      ++ia;
    } else if (ib->word < ia->word) {
      ++ib;
    } else {
      visit(ia->weight, ib->weight);
      ++ia;
      ++ib;
    }
  }
}

}  // namespace

double score(const BowVector& a, const BowVector& b) {
  // |a - b|_1 = sum over shared words of |va - vb| plus the mass of the unshared words; with
  // |a|_1 = |b|_1 = 1 only the shared words are needed (DBoW2 L1Scoring).
  double sum = 0.0;
  forSharedWords(
      a, b, [&](double va, double vb) { sum += std::abs(va - vb) - std::abs(va) - std::abs(vb); });
  return -0.5 * sum;
}

int sharedWords(const BowVector& a, const BowVector& b) {
  int count = 0;
  forSharedWords(a, b, [&](double, double) { ++count; });
  return count;
}

}  // namespace lumaslam::loop
