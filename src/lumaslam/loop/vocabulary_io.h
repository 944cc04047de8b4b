#pragma once
// Vocabulary files.
//
// Binary (ours, written by `lumaslam vocab train/convert`), little-endian:
//   char[8] "LUMAVOC\0" | u32 version (1) | u32 k | u32 L | u32 scoring (0 = L1)
//   | u32 weighting (0 = TF-IDF) | u32 node_count N | u32 word_count W | u32 reserved (0)
//   | u32 first_child[N] | u32 child_count[N] | u32 node_word[N] | u8 descriptors[32 N]
//   | u32 word_node[W] | f32 word_weight[W] | u64 checksum (FNV-1a over the arrays)
// Loading is a few bulk reads plus an O(N) structure check (VocabularyData's invariants).
//
// DBoW2 text (ORB-SLAM's ORBvoc.txt): first line "k L scoringType weightingType", then one
// line per node except the root, "parentId isLeaf d0 ... d31 weight", a node's id being its
// line number after the header (root = 0). Only L1 scoring and TF-IDF weighting (0 0) are
// accepted, as those are what ORB-SLAM uses.
#include <cstdint>
#include <filesystem>

#include "lumaslam/loop/vocabulary.h"

namespace lumaslam::loop {

// Throw Error naming the file (and line, for text) and the problem.
void saveVocabulary(const Vocabulary& vocabulary, const std::filesystem::path& file);
Vocabulary loadVocabulary(const std::filesystem::path& file);

Vocabulary loadDbow2Text(const std::filesystem::path& file);
void saveDbow2Text(const Vocabulary& vocabulary, const std::filesystem::path& file);

// Our binary format if the file starts with its magic, DBoW2 text otherwise.
Vocabulary loadAnyVocabulary(const std::filesystem::path& file);
bool isBinaryVocabulary(const std::filesystem::path& file);

// What a map file records of the vocabulary its keyframes were indexed with: the checksum of
// its tree (k, L, nodes, words, weights), the same for a binary file and its DBoW2 text.
std::uint64_t vocabularyFingerprint(const Vocabulary& vocabulary);

}  // namespace lumaslam::loop
