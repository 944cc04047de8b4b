#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <map>

#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include "error_of.h"
#include "lumaslam/core/error.h"
#include "lumaslam/core/settings_file.h"
#include "lumaslam/core/settings_spellings.h"
#include "test_paths.h"

using lumaslam::Error;
using lumaslam::core::SettingsFile;

namespace {

const char* kOrbSlamStyle = R"(%YAML:1.0
Camera.type: "PinHole"
Camera.fx: 535.4
Camera.width: 640
Camera.RGB: 1
ORBextractor.nFeatures: 1000
Enhancement:
   preset: "best"
Stereo.T_c1_c2: !!opencv-matrix
   rows: 4
   cols: 4
   dt: f
   data: [1.0, 0.0, 0.0, 0.11, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0, 0, 0, 1.0]
)";

TEST(SettingsFile, ReadsFlatAndNestedKeysWithTypes) {
  const auto s = SettingsFile::fromString(kOrbSlamStyle, "test.yaml");
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 535.4);
  EXPECT_EQ(s.get<int>("Camera.width"), 640);
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.width"), 640.0);
  EXPECT_TRUE(s.get<bool>("Camera.RGB"));
  EXPECT_EQ(s.get<std::string>("Camera.type"), "PinHole");
  EXPECT_EQ(s.get<std::string>("Enhancement.preset"), "best");
  EXPECT_EQ(s.get<int>("ORBextractor.nLevels", 8), 8);
  const cv::Mat T = s.getMatrix("Stereo.T_c1_c2", 4, 4);
  EXPECT_EQ(T.type(), CV_64F);
  EXPECT_NEAR(T.at<double>(0, 3), 0.11, 1e-6);
}

TEST(SettingsFile, ErrorsNameFileKeyAndExpectedType) {
  const auto s = SettingsFile::fromString(kOrbSlamStyle, "test.yaml");
  // A missing key is not accepted.
  const std::string message = lumaslam::test::errorOf([&] { (void)s.get<double>("Camera.fy"); });
  EXPECT_NE(message.find("test.yaml"), std::string::npos);
  EXPECT_NE(message.find("Camera.fy"), std::string::npos);
  EXPECT_NE(message.find("number"), std::string::npos);
  EXPECT_THROW((void)s.get<double>("Camera.type"), Error);  // string where number expected
  EXPECT_THROW((void)s.get<int>("Camera.fx"), Error);       // 535.4 is no integer
  EXPECT_THROW((void)s.get<int>("Camera.type", 3), Error);  // present but wrong type
  EXPECT_THROW((void)s.getMatrix("Stereo.T_c1_c2", 3, 3), Error);
}

TEST(SettingsFile, DottedKeyUnderAScalarIsMissing) {
  // Found by fuzz/settings_fuzz.cpp: the nested lookup of Camera.fx indexed the scalar
  // `Camera: 500` and OpenCV's isMap() assertion (cv::Exception) escaped.
  const auto s = SettingsFile::fromString("Camera: 500\nCamera.fy: 500\n", "scalar.yaml");
  EXPECT_FALSE(s.has("Camera.fx"));
  EXPECT_EQ(lumaslam::test::errorOf([&] { (void)s.get<double>("Camera.fx"); }),
            "scalar.yaml: key 'Camera.fx' is missing (expected number)");
}

TEST(SettingsFile, TopLevelThatIsNoMapIsAClearError) {
  // Found by fuzz/settings_fuzz.cpp: "-- Y" parses to a non-map root and the first lookup
  // escaped as OpenCV's isMap() assertion.
  for (const std::string text : {"-- Y", "- 1\n- 2\n"}) {
    EXPECT_EQ(lumaslam::test::errorOf([&] { (void)SettingsFile::fromString(text, "list.yaml"); }),
              "list.yaml: not a valid settings file: the top level is not a map of "
              "'key: value' lines")
        << "for '" << text << "'";
  }
}

TEST(SettingsFile, BytesThatMadeOpenCvsParserThrowAreAClearError) {
  // Found by fuzz/settings_fuzz.cpp: these bytes made cv::FileStorage throw std::length_error
  // (caught as "not a valid settings file (basic_string::_M_create)"). They are not UTF-8, so
  // they are now refused before OpenCV reads them; the catch stays for any other such input.
  const auto file = std::filesystem::path(LUMASLAM_SOURCE_DIR) /
                    "fuzz/regressions/settings/opencv_parser_length_error.yaml";
  const std::string expected =
      file.string() + ": line 7: not UTF-8 text (byte 0xbc at column 1); YAML files are text";
  EXPECT_EQ(lumaslam::test::errorOf([&] { (void)SettingsFile::open(file); }), expected);
}

TEST(SettingsFile, MatrixShapeIsCheckedBeforeOpenCvAllocatesIt) {
  // Found by fuzz/settings_fuzz.cpp: cv::read allocated rows x cols (64 GB) from the header.
  const auto s = SettingsFile::fromString(
      "M: !!opencv-matrix\n  rows: 4\n  cols: 1000000000\n  dt: d\n  data: [1]\n"
      "N: !!opencv-matrix\n  rows: 4\n  cols: x\n  dt: d\n  data: [1]\n",
      "m.yaml");
  EXPECT_EQ(lumaslam::test::errorOf([&] { (void)s.getMatrix("M", 4, 4); }),
            "m.yaml: key 'M': expected a 4x4 matrix, found 4x1000000000");
  EXPECT_THROW((void)s.getMatrix("N", 4, 4), Error);
}

TEST(SettingsFile, MissingOrBrokenFileIsAClearError) {
  lumaslam::test::TempDir dir("settings");
  EXPECT_THROW((void)SettingsFile::open(dir.path() / "nope.yaml"), Error);
  const auto broken = dir.path() / "broken.yaml";
  std::ofstream(broken) << "%YAML:1.0\nCamera.fx: [1, 2\n  : :\n";
  // Broken YAML is not accepted.
  EXPECT_NE(lumaslam::test::errorOf([&] { (void)SettingsFile::open(broken); }).find("broken.yaml"),
            std::string::npos);
}

// The Error that parsing `yaml` as settings.yaml raises (test::errorOf).
std::string errorOf(const std::string& yaml) {
  return lumaslam::test::errorOf([&] { (void)SettingsFile::fromString(yaml, "settings.yaml"); });
}

TEST(SettingsFile, DuplicateKeyNamesTheKeyAndBothLines) {
  EXPECT_EQ(errorOf("%YAML:1.0\nCamera.fx: 1\nCamera.fy: 2\nCamera.fx: 3\n"),
            "settings.yaml: key 'Camera.fx' is set twice: lines 2 and 4");
  // Nested maps are flattened: the same key written flat and nested is set twice too.
  EXPECT_EQ(errorOf("System:\n  sequential: 1\n  sequential: 0\n"),
            "settings.yaml: key 'System.sequential' is set twice: lines 2 and 3");
  EXPECT_EQ(errorOf("%YAML:1.0\n---\nCamera.fx: 1  # focal\n\nCamera:\n   fy: 2\n   fx: 3\n"),
            "settings.yaml: key 'Camera.fx' is set twice: lines 3 and 7");
}

TEST(SettingsFile, KeyLikeTextInCommentsStringsAndListsIsNoDuplicate) {
  const auto s = SettingsFile::fromString(
      "%YAML:1.0\n"
      "# Camera.fx: 2\n"
      "Camera.fx: 1 # Camera.fx: 3\n"
      "Name: \"Camera.fx: 4\"\n"
      "Enhancement:\n"
      "  preset: \"best\"\n"
      "Detector:\n"
      "  preset: \"none\"\n"
      "Stereo.T_c1_c2: !!opencv-matrix\n"
      "   rows: 1\n"
      "   cols: 2\n"
      "   dt: d\n"
      "   data: [ 1.0,\n"
      "           2.0 ]\n"
      "Other.T: !!opencv-matrix\n"
      "   rows: 1\n"
      "   cols: 2\n"
      "   dt: d\n"
      "   data: [ 1.0, 2.0 ]\n",
      "settings.yaml");
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 1.0);
  EXPECT_EQ(s.get<std::string>("Detector.preset"), "none");
}

TEST(SettingsFile, SyntaxErrorNamesFileAndLine) {
  // An unclosed '[' is found where the next key starts (line 4 of the file as written).
  EXPECT_EQ(errorOf("%YAML:1.0\nCamera.fx: 1\nCamera.fy: [1, 2\nCamera.cx: 3\n"),
            "settings.yaml: line 4: not a valid settings file: Incorrect indentation");
  // Without the %YAML header (added before parsing) the line is still the file's own.
  EXPECT_EQ(errorOf("Camera:\n  fx: 1\n   fy: 2\n"),
            "settings.yaml: line 3: not a valid settings file: Incorrect indentation");
}

TEST(SettingsFile, Utf8ByteOrderMarkIsSkipped) {
  const auto with_header = SettingsFile::fromString("\xEF\xBB\xBF%YAML:1.0\nCamera.fx: 535.4\n");
  EXPECT_DOUBLE_EQ(with_header.get<double>("Camera.fx"), 535.4);
  const auto without_header = SettingsFile::fromString(
      "\xEF\xBB\xBF"
      "Camera.fx: 535.4\n");
  EXPECT_DOUBLE_EQ(without_header.get<double>("Camera.fx"), 535.4);
  EXPECT_EQ(without_header.keys(), std::vector<std::string>{"Camera.fx"});
}

TEST(SettingsFile, IntegerOutOfRangeIsReportedAsWritten) {
  const auto s = SettingsFile::fromString(
      "ORBextractor.nFeatures: 3000000000\nORBextractor:\n  nLevels: -3e9\nCamera.fx: 3e9\n",
      "settings.yaml");
  // 3000000000 is not read as an int.
  EXPECT_EQ(lumaslam::test::errorOf([&] { (void)s.get<int>("ORBextractor.nFeatures"); }),
            "settings.yaml: key 'ORBextractor.nFeatures': 3000000000 is out of range "
            "(expected an integer from -2147483648 to 2147483647)");
  EXPECT_THROW((void)s.get<int>("ORBextractor.nLevels", 8), Error);
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 3e9);  // a number, not an integer: fine
}

}  // namespace

// OpenCV 4.6's YAML parser never returns on these (found by fuzzing, fuzz/regressions/): a
// line that starts with the document marker "---" directly followed by text is refused first.
TEST(SettingsFile, DocumentMarkerWithTextIsRefusedBeforeOpenCvsParserLoops) {
  EXPECT_EQ(errorOf("----x\nS\n:"),
            "settings.yaml: line 1: '---' (a YAML document marker) must be followed by a blank "
            "or end the line");
  EXPECT_EQ(errorOf("%YAML:1.0\nCamera.fx: 1\n---YAML: 2\n"),
            "settings.yaml: line 3: '---' (a YAML document marker) must be followed by a blank "
            "or end the line");
  // The marker alone, with blanks or a comment, is YAML as ORB-SLAM3 files write it.
  const auto s = SettingsFile::fromString("%YAML:1.0\n---  # settings\nCamera.fx: 535.4\n");
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 535.4);
}

// OpenCV 4.6's YAML parser also never returns on some inputs with bytes that are not UTF-8
// (found by fuzzing settings files and EuRoC sensor.yaml, fuzz/regressions/): such text, and
// NUL bytes, are refused first, naming the line, the byte and its column. UTF-8 passes.
TEST(SettingsFile, BytesThatAreNotUtf8AreRefusedBeforeOpenCvsParserLoops) {
  EXPECT_EQ(errorOf("%oT\xa5"
                    "9,\n    -\xf3\xff\xff"
                    "an\n\x90\n.n"),
            "settings.yaml: line 1: not UTF-8 text (byte 0xa5 at column 4); YAML files are text");
  EXPECT_EQ(errorOf("Camera.fx: 1\nCamera.fy: 2\xff\n"),
            "settings.yaml: line 2: not UTF-8 text (byte 0xff at column 13); YAML files are text");
  EXPECT_EQ(errorOf(std::string("Camera.fx: 1\n\0\n", 15)),
            "settings.yaml: line 2: not UTF-8 text (byte 0x00 at column 1); YAML files are text");
  EXPECT_EQ(errorOf("Camera.fx: 1 # \xc3\n"),  // a lead byte without its continuation
            "settings.yaml: line 1: not UTF-8 text (byte 0xc3 at column 16); YAML files are text");
  const auto s =
      SettingsFile::fromString("Camera.fx: 535.4  # Brennweite f\xc3\xbcr x, \xe2\x82\xac\n");
  EXPECT_DOUBLE_EQ(s.get<double>("Camera.fx"), 535.4);
}

// Keys renamed to camelCase (issue 21, core/settings_spellings.h): the old snake_case spelling
// is read in place of the new name, with one warning naming the file, the old and the new key.
namespace spellings {
namespace {

std::string loggedWhile(const std::function<void()>& work) {
  const auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(32);
  const auto logger = spdlog::default_logger();
  logger->sinks().push_back(sink);
  work();
  logger->sinks().pop_back();
  std::string logged;
  for (const auto& line : sink->last_formatted()) logged += line;
  return logged;
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(SettingsFileSpellings, OldSpellingIsReadWithOneWarning) {
  const auto old_file = SettingsFile::fromString("Detector.queue_capacity: 7\n", "settings.yaml");
  const auto new_file = SettingsFile::fromString("Detector.queueCapacity: 7\n", "settings.yaml");
  std::optional<int> read_old;
  const std::string logged = loggedWhile([&] {
    read_old = old_file.find<int>("Detector.queueCapacity");
    EXPECT_TRUE(old_file.has("Detector.queueCapacity"));  // a second read: no second warning
  });
  EXPECT_EQ(read_old, new_file.find<int>("Detector.queueCapacity"));
  EXPECT_EQ(read_old, 7);
  const std::string warning =
      "settings.yaml: 'Detector.queue_capacity' is an old spelling; use 'Detector.queueCapacity'";
  EXPECT_EQ(count(logged, warning), 1U) << logged;
  EXPECT_TRUE(lumaslam::core::unknownKeys(old_file).empty());
  EXPECT_EQ(loggedWhile([&] { (void)new_file.find<int>("Detector.queueCapacity"); }), "");
}

TEST(SettingsFileSpellings, NestedOldSpellingIsReadToo) {
  const auto file = SettingsFile::fromString(
      "Enhancement:\n  clahe:\n    tiles_x: 3\n    fixed_limit: 2.5\n", "nested.yaml");
  EXPECT_EQ(file.get<int>("Enhancement.clahe.tilesX", 8), 3);
  EXPECT_DOUBLE_EQ(file.get<double>("Enhancement.clahe.fixedLimit", 2.0), 2.5);
  EXPECT_TRUE(lumaslam::core::unknownKeys(file).empty());
}

TEST(SettingsFileSpellings, BothSpellingsAreAnErrorNamingBoth) {
  const auto file = SettingsFile::fromString(
      "Enhancement.clahe.tiles_x: 4\nEnhancement.clahe.tilesX: 4\n", "both.yaml");
  const std::string what =
      lumaslam::test::errorOf([&] { (void)file.find<int>("Enhancement.clahe.tilesX"); });
  EXPECT_NE(what.find("both.yaml"), std::string::npos) << what;
  EXPECT_NE(what.find("'Enhancement.clahe.tilesX'"), std::string::npos) << what;
  EXPECT_NE(what.find("'Enhancement.clahe.tiles_x'"), std::string::npos) << what;
}

TEST(SettingsFileSpellings, AWrongTypeNamesTheKeyAsWritten) {
  const auto file = SettingsFile::fromString("Detector.mask_margin: wide\n", "type.yaml");
  const std::string message =
      lumaslam::test::errorOf([&] { (void)file.find<int>("Detector.maskMargin"); });
  EXPECT_NE(message.find("key 'Detector.mask_margin': expected integer"), std::string::npos)
      << message;
}

// "Did you mean" suggests the new names, also for a typo of an old spelling.
TEST(SettingsFileSpellings, TyposAreAnsweredWithTheNewName) {
  const auto file =
      SettingsFile::fromString("Detector.queueCapacty: 3\nDetector.memory_frame: 2\n", "typo.yaml");
  (void)file.find<int>("Detector.queueCapacity");
  (void)file.find<int>("Detector.memoryFrames");
  std::map<std::string, std::string> found;
  for (const auto& [key, suggestion] : lumaslam::core::unknownKeys(file)) found[key] = suggestion;
  EXPECT_EQ(found["Detector.queueCapacty"], "Detector.queueCapacity");
  EXPECT_EQ(found["Detector.memory_frame"], "Detector.memoryFrames");
}

TEST(SettingsFileSpellings, EveryOldSpellingIsSnakeCaseAndEveryNewOneCamelCase) {
  for (const auto& [old_key, new_key] : lumaslam::core::keySpellings()) {
    EXPECT_NE(old_key.find('_'), std::string_view::npos) << old_key;
    EXPECT_EQ(new_key.find('_'), std::string_view::npos) << new_key;
    EXPECT_EQ(lumaslam::core::oldSpellingOf(new_key), old_key);
    EXPECT_EQ(lumaslam::core::newSpellingOf(old_key), new_key);
  }
}

}  // namespace
}  // namespace spellings
