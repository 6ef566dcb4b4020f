#include "config_loader.hpp"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <fstream>
#include <sstream>

namespace pena::services {
namespace {

// Keeps the first error with its position (protobuf counts lines and columns from 0).
class FirstError : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, google::protobuf::io::ColumnNumber column,
                const std::string& message) override {
    if (!message_.empty()) return;
    line_ = static_cast<std::size_t>(line) + 1;
    message_ = "column " + std::to_string(column + 1) + ": " + message;
  }
  void AddWarning(int /*line*/, google::protobuf::io::ColumnNumber /*column*/,
                  const std::string& /*message*/) override {}
  std::size_t line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  std::size_t line_ = 0;
  std::string message_;
};

}  // namespace

void LoadTextConfigInto(const std::filesystem::path& path, google::protobuf::Message& message) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path, 0, "cannot open the config file");
  std::ostringstream text;
  text << in.rdbuf();
  FirstError errors;
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  parser.AllowUnknownField(false);
  parser.AllowUnknownExtension(false);
  message.Clear();
  if (!parser.ParseFromString(text.str(), &message)) {
    throw io::InputError(path, errors.line(),
                         errors.message().empty() ? "cannot parse the config" : errors.message());
  }
}

std::filesystem::path ResolvePath(const std::filesystem::path& config_path,
                                  const std::string& relative) {
  const std::filesystem::path given(relative);
  if (given.is_absolute() || config_path.empty()) return given;
  return config_path.parent_path() / given;
}

}  // namespace pena::services
