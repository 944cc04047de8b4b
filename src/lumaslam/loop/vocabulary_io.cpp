#include "lumaslam/loop/vocabulary_io.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lumaslam/core/checksum.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/read_file.h"
#include "lumaslam/io/output_file.h"

namespace lumaslam::loop {

namespace {

constexpr std::array<char, 8> kMagic = {'L', 'U', 'M', 'A', 'V', 'O', 'C', '\0'};
constexpr std::uint32_t kVersion = 1;

struct Header {
  std::array<char, 8> magic = kMagic;
  std::uint32_t version = kVersion;
  std::uint32_t branching = 0;
  std::uint32_t depth = 0;
  std::uint32_t scoring = 0;
  std::uint32_t weighting = 0;
  std::uint32_t node_count = 0;
  std::uint32_t word_count = 0;
  std::uint32_t reserved = 0;
};
static_assert(sizeof(Header) == 40);

using core::Checksum;

template <typename T>
std::size_t bytesOf(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

template <typename Data, typename F>  // Data: VocabularyData, const or not
void forEachArray(Data& d, F&& f) {
  f(d.first_child.data(), bytesOf(d.first_child));
  f(d.child_count.data(), bytesOf(d.child_count));
  f(d.node_word.data(), bytesOf(d.node_word));
  f(d.descriptors.data(), bytesOf(d.descriptors));
  f(d.word_node.data(), bytesOf(d.word_node));
  f(d.word_weight.data(), bytesOf(d.word_weight));
}

// Splits on spaces/tabs; at most `max` fields (one more means "too many").
using Fields = std::array<std::string_view, 36>;

int splitFields(std::string_view line, Fields& fields) {
  int count = 0;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (count == static_cast<int>(fields.size())) return count + 1;
    fields[static_cast<std::size_t>(count++)] = line.substr(i, j - i);
    i = j;
  }
  return count;
}

template <typename T>
bool parseNumber(std::string_view text, T& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

// Parsed DBoW2 node (file order; index 0 = root).
struct TextNode {
  std::uint32_t parent = 0;
  bool leaf = false;
  float weight = 0.0F;
  std::vector<std::uint32_t> children;
};

// Node order for our layout: the file order when it already has every node's children
// contiguous and after their parent (what DBoW2 writes), else breadth-first.
std::vector<std::uint32_t> layoutOrder(const std::vector<TextNode>& nodes) {
  std::vector<std::uint32_t> order(nodes.size());
  bool contiguous = true;
  for (const auto& node : nodes) {
    for (std::size_t c = 1; c < node.children.size(); ++c) {
      contiguous &= node.children[c] == node.children[c - 1] + 1;
    }
  }
  if (contiguous) {
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    return order;
  }
  std::size_t head = 0;
  std::size_t tail = 1;
  order[0] = 0;
  while (head < tail) {
    for (const std::uint32_t child : nodes[order[head]].children) order[tail++] = child;
    ++head;
  }
  return order;
}

VocabularyData toData(const std::vector<TextNode>& nodes, const std::vector<std::uint8_t>& desc,
                      int branching, int depth) {
  const std::vector<std::uint32_t> order = layoutOrder(nodes);  // new id -> file id
  std::vector<std::uint32_t> new_id(nodes.size());
  for (std::uint32_t n = 0; n < order.size(); ++n) new_id[order[n]] = n;
  VocabularyData data;
  data.branching = branching;
  data.depth = depth;
  const std::size_t count = nodes.size();
  data.first_child.assign(count, 0);
  data.child_count.assign(count, 0);
  data.node_word.assign(count, kNoWord);
  data.descriptors.resize(count * kDescriptorBytes);
  for (std::uint32_t n = 0; n < count; ++n) {
    const TextNode& node = nodes[order[n]];
    std::memcpy(&data.descriptors[n * kDescriptorBytes], &desc[order[n] * kDescriptorBytes],
                kDescriptorBytes);
    if (!node.children.empty()) {
      data.first_child[n] = new_id[node.children.front()];
      data.child_count[n] = static_cast<std::uint32_t>(node.children.size());
    } else if (n != 0) {
      // A childless node is a word even if flagged inner (DBoW2 treats it the same way when
      // descending: it stops there).
      data.node_word[n] = static_cast<WordId>(data.word_node.size());
      data.word_node.push_back(n);
      data.word_weight.push_back(node.weight);
    }
  }
  return data;
}

// The lines of a text, numbered from 1.
struct TextLines {
  std::string_view rest;
  std::size_t line_number = 0;
  bool next(std::string_view& line) {
    if (rest.empty()) return false;
    const std::size_t end = rest.find('\n');
    line = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
    ++line_number;
    return true;
  }
};

// The header line 'k L scoringType weightingType': k and L, in range; only L1 / TF-IDF.
std::pair<int, int> parseDbow2Header(std::string_view line, const std::string& name,
                                     Fields& fields) {
  int header[4] = {0, 0, 0, 0};
  if (splitFields(line, fields) != 4 || !parseNumber(fields[0], header[0]) ||
      !parseNumber(fields[1], header[1]) || !parseNumber(fields[2], header[2]) ||
      !parseNumber(fields[3], header[3])) {
    fail("{}:1: expected DBoW2 header 'k L scoringType weightingType', got '{}'", name,
         line.substr(0, 80));
  }
  const int branching = header[0];
  const int depth = header[1];
  if (branching < 2 || branching > 256 || depth < 1 || depth > 32) {
    fail("{}:1: k = {}, L = {} out of range (k 2..256, L 1..32)", name, branching, depth);
  }
  if (header[2] != 0 || header[3] != 0) {
    fail("{}:1: scoring type {} / weighting type {} not supported (only 0 0: L1, TF-IDF)", name,
         header[2], header[3]);
  }
  return {branching, depth};
}

// A node line 'parentId isLeaf d0..d31 weight' (`count` fields) after `node_count` nodes; its
// descriptor is appended to `desc`.
TextNode parseDbow2Node(const Fields& fields, int count, std::size_t node_count,
                        const std::string& name, std::size_t line_number,
                        std::vector<std::uint8_t>& desc) {
  if (count != 2 + kDescriptorBytes + 1) {
    fail("{}:{}: expected {} fields 'parentId isLeaf d0..d31 weight', found {}", name, line_number,
         2 + kDescriptorBytes + 1, count);
  }
  TextNode node;
  int leaf = 0;
  double weight = 0.0;
  if (!parseNumber(fields[0], node.parent) || node.parent >= node_count) {
    fail("{}:{}: parent id '{}' is not an earlier node (0..{})", name, line_number, fields[0],
         node_count - 1);
  }
  if (!parseNumber(fields[1], leaf) || (leaf != 0 && leaf != 1)) {
    fail("{}:{}: isLeaf '{}' must be 0 or 1", name, line_number, fields[1]);
  }
  node.leaf = leaf == 1;
  for (int b = 0; b < kDescriptorBytes; ++b) {
    int value = 0;
    if (!parseNumber(fields[2 + b], value) || value < 0 || value > 255) {
      fail("{}:{}: descriptor byte {} '{}' must be 0..255", name, line_number, b, fields[2 + b]);
    }
    desc.push_back(static_cast<std::uint8_t>(value));
  }
  if (!parseNumber(fields[2 + kDescriptorBytes], weight) || !std::isfinite(weight) ||
      weight < 0.0) {
    fail("{}:{}: weight '{}' must be a finite number >= 0", name, line_number,
         fields[2 + kDescriptorBytes]);
  }
  node.weight = static_cast<float>(weight);
  return node;
}

// The tree read so far (node 0 the root): a node joins it under its parent if that is no
// leaf, has fewer than k children and is above level L.
struct TextTree {
  int branching = 0;
  int depth = 0;
  std::vector<TextNode> nodes = std::vector<TextNode>(1);
  std::vector<int> level = std::vector<int>(1, 0);

  void add(const TextNode& node, const std::string& name, std::size_t line_number) {
    TextNode& parent = nodes[node.parent];
    if (node.parent != 0 && parent.leaf) {
      fail("{}:{}: parent {} is a leaf", name, line_number, node.parent);
    }
    if (parent.children.size() >= static_cast<std::size_t>(branching)) {
      fail("{}:{}: node {} would get more than k = {} children", name, line_number, node.parent,
           branching);
    }
    const int node_level = level[node.parent] + 1;
    if (node_level > depth) {
      fail("{}:{}: node at depth {} exceeds L = {}", name, line_number, node_level, depth);
    }
    const auto id = static_cast<std::uint32_t>(nodes.size());
    parent.children.push_back(id);
    nodes.push_back(node);
    level.push_back(node_level);
  }
};

}  // namespace

void saveVocabulary(const Vocabulary& vocabulary, const std::filesystem::path& file) {
  const VocabularyData& data = vocabulary.data();
  Header header;
  header.branching = static_cast<std::uint32_t>(data.branching);
  header.depth = static_cast<std::uint32_t>(data.depth);
  header.node_count = static_cast<std::uint32_t>(data.nodeCount());
  header.word_count = static_cast<std::uint32_t>(data.wordCount());
  io::OutputFile output(file);  // FILE.partial, renamed into place when complete
  std::ostream& out = output.stream();
  out.write(reinterpret_cast<const char*>(&header), sizeof(header));
  Checksum checksum;
  forEachArray(data, [&](const void* p, std::size_t size) {
    out.write(static_cast<const char*>(p), static_cast<std::streamsize>(size));
    checksum.update(p, size);
  });
  const std::uint64_t sum = checksum.value();
  out.write(reinterpret_cast<const char*>(&sum), sizeof(sum));
  output.commit();
}

Vocabulary loadVocabulary(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("{}: cannot open vocabulary file", name);
  in.seekg(0, std::ios::end);
  const auto file_size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  Header header;
  const std::size_t header_bytes = std::min<std::uint64_t>(file_size, sizeof(Header));
  in.read(reinterpret_cast<char*>(&header), static_cast<std::streamsize>(header_bytes));
  if (!in || header_bytes < kMagic.size() || header.magic != kMagic) {
    fail(
        "{}: not a lumaslam binary vocabulary (for DBoW2 text such as ORBvoc.txt use "
        "`lumaslam vocab convert`)",
        name);
  }
  if (header_bytes < sizeof(Header)) {
    fail("{}: {} bytes, shorter than the {}-byte header: truncated", name, file_size,
         sizeof(Header));
  }
  if (header.version != kVersion) {
    fail("{}: vocabulary format version {} (this build reads version {})", name, header.version,
         kVersion);
  }
  if (header.scoring != 0 || header.weighting != 0) {
    fail("{}: scoring {} / weighting {} not supported (only L1 / TF-IDF)", name, header.scoring,
         header.weighting);
  }
  const std::uint64_t nodes = header.node_count;
  const std::uint64_t words = header.word_count;
  const std::uint64_t expected =
      sizeof(Header) + nodes * (3 * 4 + kDescriptorBytes) + words * (4 + 4) + 8;
  if (file_size != expected) {
    fail("{}: {} bytes but the header ({} nodes, {} words) needs {}: truncated or corrupt", name,
         file_size, nodes, words, expected);
  }
  VocabularyData data;
  data.branching = static_cast<int>(std::min<std::uint32_t>(header.branching, INT32_MAX));
  data.depth = static_cast<int>(std::min<std::uint32_t>(header.depth, INT32_MAX));
  data.first_child.resize(nodes);
  data.child_count.resize(nodes);
  data.node_word.resize(nodes);
  data.descriptors.resize(nodes * kDescriptorBytes);
  data.word_node.resize(words);
  data.word_weight.resize(words);
  Checksum checksum;
  forEachArray(data, [&](void* p, std::size_t size) {
    in.read(static_cast<char*>(p), static_cast<std::streamsize>(size));
    checksum.update(p, size);
  });
  std::uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(&stored), sizeof(stored));
  if (!in) fail("{}: cannot read vocabulary arrays", name);
  if (stored != checksum.value()) {
    fail("{}: checksum mismatch (stored {:016x}, computed {:016x}): the file is corrupt", name,
         stored, checksum.value());
  }
  return Vocabulary(std::move(data), name);
}

Vocabulary loadDbow2Text(const std::filesystem::path& file) {
  const std::string name = file.string();
  const std::string text = core::readWholeFile(file, "vocabulary file");
  TextLines lines{text};
  Fields fields;
  std::string_view line;
  if (!lines.next(line))
    fail("{}: empty file (expected DBoW2 header 'k L scoring weighting')", name);
  const auto [branching, depth] = parseDbow2Header(line, name, fields);

  TextTree tree{branching, depth};
  std::vector<std::uint8_t> desc(kDescriptorBytes, 0);
  while (lines.next(line)) {
    const int count = splitFields(line, fields);
    if (count == 0) continue;  // blank line (e.g. the final newline)
    const TextNode node =
        parseDbow2Node(fields, count, tree.nodes.size(), name, lines.line_number, desc);
    tree.add(node, name, lines.line_number);
  }
  if (tree.nodes.size() == 1) fail("{}: no nodes after the header", name);
  return Vocabulary(toData(tree.nodes, desc, branching, depth), name);
}

void saveDbow2Text(const Vocabulary& vocabulary, const std::filesystem::path& file) {
  const VocabularyData& d = vocabulary.data();
  std::vector<std::uint32_t> parent(d.nodeCount(), 0);
  for (std::uint32_t n = 0; n < d.nodeCount(); ++n) {
    for (std::uint32_t c = 0; c < d.child_count[n]; ++c) parent[d.first_child[n] + c] = n;
  }
  std::string text = fmt::format("{} {} 0 0\n", d.branching, d.depth);
  for (std::uint32_t n = 1; n < d.nodeCount(); ++n) {
    const bool leaf = d.child_count[n] == 0;
    fmt::format_to(std::back_inserter(text), "{} {}", parent[n], leaf ? 1 : 0);
    const std::uint8_t* descriptor = vocabulary.nodeDescriptor(n);
    for (int b = 0; b < kDescriptorBytes; ++b) {
      fmt::format_to(std::back_inserter(text), " {}", descriptor[b]);
    }
    fmt::format_to(std::back_inserter(text), " {}\n", leaf ? d.word_weight[d.node_word[n]] : 0.0F);
  }
  io::OutputFile output(file);
  output.stream().write(text.data(), static_cast<std::streamsize>(text.size()));
  output.commit();
}

bool isBinaryVocabulary(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<char, 8> magic{};
  return in.read(magic.data(), magic.size()) && magic == kMagic;
}

Vocabulary loadAnyVocabulary(const std::filesystem::path& file) {
  return isBinaryVocabulary(file) ? loadVocabulary(file) : loadDbow2Text(file);
}

std::uint64_t vocabularyFingerprint(const Vocabulary& vocabulary) {
  const VocabularyData& data = vocabulary.data();
  Checksum checksum;
  const std::uint32_t shape[2] = {static_cast<std::uint32_t>(data.branching),
                                  static_cast<std::uint32_t>(data.depth)};
  checksum.update(shape, sizeof(shape));
  forEachArray(data, [&](const void* p, std::size_t size) { checksum.update(p, size); });
  return checksum.value();
}

}  // namespace lumaslam::loop
