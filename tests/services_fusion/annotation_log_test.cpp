#include "annotation_log.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace pena::services {
namespace {

pena_dds::Annotation Mark(const std::string& id, pena_dds::AnnotationKind kind, double x_m,
                          const std::string& text, bool retracted = false) {
  pena_dds::Annotation mark;
  mark.annotation_id(id);
  mark.author_id("op");
  mark.kind(kind);
  mark.position().x_m(x_m);
  mark.position().y_m(-2.0);
  mark.text(text);
  mark.retracted(retracted);
  return mark;
}

TEST(AnnotationLog, GivesTheLastSampleOfEachMarkAcrossAReopen) {
  const auto path = std::filesystem::path(testing::TempDir()) / "annotation_log_test.cdr";
  std::filesystem::remove(path);
  {
    AnnotationLog log(path);
    log.Append(Mark("op/1", pena_dds::ANNOTATION_VICTIM_FOUND, 1.0, "two people, a comma"));
    log.Append(Mark("op/2", pena_dds::ANNOTATION_EXIT, 5.0, "exit"));
    log.Append(Mark("op/1", pena_dds::ANNOTATION_VICTIM_FOUND, 1.5, "two people, a comma"));  // moved
    log.Append(Mark("op/2", pena_dds::ANNOTATION_EXIT, 5.0, "exit", true));                    // retracted
    log.Append(Mark("op/2", pena_dds::ANNOTATION_EXIT, 5.0, "exit", true));  // the same again: not kept
    EXPECT_EQ(log.records(), 4u);
  }
  // A crash while writing leaves a torn last record: it does not count, and is cut off.
  { std::ofstream(path, std::ios::app | std::ios::binary) << std::string("\x40\x00\x00\x00\x01\x02", 6); }
  {
    AnnotationLog reopened(path);
    EXPECT_EQ(reopened.records(), 4u);
    reopened.Append(Mark("op/3", pena_dds::ANNOTATION_STAIRS, 9.0, ""));
  }
  const std::vector<pena_dds::Annotation> latest = AnnotationLog(path).Latest();
  ASSERT_EQ(latest.size(), 3u);
  EXPECT_EQ(latest[0].annotation_id().to_string(), "op/1");
  EXPECT_DOUBLE_EQ(latest[0].position().x_m(), 1.5);
  EXPECT_EQ(latest[0].text().to_string(), "two people, a comma");
  EXPECT_EQ(latest[1].kind(), pena_dds::ANNOTATION_EXIT);  // not folded into "landmark"
  EXPECT_TRUE(latest[1].retracted());
  EXPECT_EQ(latest[2].kind(), pena_dds::ANNOTATION_STAIRS);
}

TEST(AnnotationLog, ARecordThatDoesNotDecodeIsAnErrorNamingFileAndByte) {
  const auto path = std::filesystem::path(testing::TempDir()) / "annotation_log_bad.cdr";
  { std::ofstream(path, std::ios::binary) << std::string("\x00\x00\x10\x00", 4) << std::string(1 << 20, 'x'); }
  try {
    AnnotationLog log(path);
    FAIL() << "a bad record was accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("annotation_log_bad.cdr: byte 0"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace pena::services
