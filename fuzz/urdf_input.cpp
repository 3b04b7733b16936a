#include "urdf_input.hpp"

#include <fstream>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/error.hpp"
#include "lagrange/reader.hpp"
#include "model_budget.hpp"

namespace lagrange::fuzz {

std::string read_urdf_bytes(const std::string& bytes, const std::string& path) {
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  try {
    const Model model = read_model_file(path);
    if (fits(model, Budget{})) (void)compile(derive(model));
    return "ok";
  } catch (const ModelError& e) {
    return e.what();
  }
}

}  // namespace lagrange::fuzz
