#include "stochnav/io/json_document.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

// Follows the parser through the document (nlohmann's parse callback) to know the JSON pointer
// of every key, and refuses a key an object already has.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string& name) : name_(&name) {}

  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
        containers_.push_back({true, {}, {}, 0});
        break;
      case Event::array_start:
        containers_.push_back({false, {}, {}, 0});
        break;
      case Event::key: {
        Container& object = containers_.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second) {
          throw InputError(*name_ + ": duplicate key at " + pointer() +
                           "; JSON objects need distinct keys: keep one of them");
        }
        break;
      }
      case Event::object_end:
      case Event::array_end:
        containers_.pop_back();
        element_done();
        break;
      case Event::value:
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Container {
    bool object = false;
    std::set<std::string> keys;  // an object's keys so far
    std::string key;             // an object's current key
    std::size_t index = 0;       // an array's current element
  };

  void element_done() {
    if (!containers_.empty() && !containers_.back().object) ++containers_.back().index;
  }

  // RFC 6901: "~" is written "~0" and "/" is written "~1".
  std::string pointer() const {
    std::string text;
    for (const Container& container : containers_) {
      text += '/';
      if (!container.object) {
        text += std::to_string(container.index);
        continue;
      }
      for (char c : container.key) {
        if (c == '~') {
          text += "~0";
        } else if (c == '/') {
          text += "~1";
        } else {
          text += c;
        }
      }
    }
    return text;
  }

  const std::string* name_;
  std::vector<Container> containers_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& name) {
  try {
    return nlohmann::json::parse(text, DuplicateKeyCheck(name));
  } catch (const nlohmann::json::parse_error& problem) {
    throw InputError(name + ": not valid JSON (" + problem.what() +
                     "); fix the syntax at that position");
  } catch (const nlohmann::json::out_of_range& problem) {
    // 406: a number the parser cannot hold in a double.
    throw InputError(name + ": a number is out of range (" + problem.what() +
                     "); numbers must lie within +/-1.7e308");
  } catch (const nlohmann::json::exception& problem) {
    throw InputError(name + ": not valid JSON (" + problem.what() + "); fix the file");
  }
}

nlohmann::json read_json_document(const std::filesystem::path& path, std::string_view what) {
  const std::string name = path.string();
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(name + ": is a folder, not a JSON file; give " + std::string(what) +
                     " as a file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(name + ": cannot open (" + std::strerror(errno) + "); check the path of " +
                     std::string(what));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    throw InputError(name + ": read error (" + std::strerror(errno) + "); check the file");
  }
  return parse_json_document(text.str(), name);
}

}  // namespace stochnav
