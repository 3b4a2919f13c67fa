// make_subject16_graph SUBJECT16_FOLDER OUT.mgraph: writes the subject-16 graph built in process
// (subject16_build.h), for the CTest fixture "subject16_graph".
#include <cstdio>
#include <exception>

#include "motiongraph/io/file.h"
#include "pipeline/subject16_build.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_subject16_graph SUBJECT16_FOLDER OUT.mgraph\n");
    return 2;
  }
  try {
    const mg::GraphFile file = mg::test::build_subject16_graph(argv[1]);
    if (auto s = mg::write_file_atomic(argv[2], mg::serialize_graph_file(file)); !s) {
      std::fprintf(stderr, "%s\n", s.error().to_string().c_str());
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
