#include "test_data.h"

#include <stdexcept>

#include "motiongraph/io/file.h"
#include "motiongraph/motion/clip_loader.h"

namespace mg::test {

std::string data_path(const std::string& relative) { return std::string(MOTIONGRAPH_DATA_DIR) + "/" + relative; }

std::string read_data(const std::string& relative) {
  auto text = read_text_file(data_path(relative));
  if (!text) throw std::runtime_error(text.error().to_string());
  return std::move(*text);
}

Clip load_data_clip(const std::string& relative, double bvh_metres_per_unit, double input_fps) {
  ClipLoadSettings settings;
  settings.bvh_metres_per_unit = bvh_metres_per_unit;
  settings.input_fps = input_fps;
  ClipLoader loader(settings);
  auto loaded = loader.load(data_path(relative));
  if (!loaded) throw std::runtime_error(loaded.error().to_string());
  return std::move(loaded->clip);
}

double max_position_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.size() != b.size()) throw std::runtime_error("position arrays differ in size");
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  return worst;
}

}  // namespace mg::test
