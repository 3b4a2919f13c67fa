#include "synthesis/subject16_graph.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

#include "motiongraph/io/file.h"

namespace mg::test {

const Subject16& subject16() {
  static const std::unique_ptr<Subject16> loaded = [] {
    const char* path = std::getenv("MOTIONGRAPH_TEST_GRAPH");
    if (path == nullptr) {
      throw std::runtime_error("MOTIONGRAPH_TEST_GRAPH is not set: run the tests through ctest, whose fixture "
                               "builds the subject-16 graph");
    }
    auto bytes = read_text_file(path);
    if (!bytes) throw std::runtime_error(bytes.error().to_string());
    auto file = parse_graph_file(*bytes, path);
    if (!file) throw std::runtime_error(file.error().to_string());
    auto s = std::make_unique<Subject16>();
    s->file = std::move(*file);
    auto context = make_synthesis_context(s->file.database, s->file.graph);
    if (!context) throw std::runtime_error(context.error().to_string());
    s->context = std::move(*context);
    return s;
  }();
  return *loaded;
}

}  // namespace mg::test
