// `lagrange export MODEL --fmu out.fmu`: export_c's C, the FMU's C (src/io/fmu/), the FMI 2.0
// headers and modelDescription.xml, compiled to binaries/linux64/<id>.so and zipped (docs/fmu.md).

#include <fmt/format.h>
#include <stdlib.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "compile/c_compiler.hpp"
#include "compile/sha256.hpp"
#include "io/fmu_files.hpp"
#include "io/fmu_layout.hpp"
#include "io/zip_writer.hpp"
#include "lagrange/io.hpp"
#include "lagrange/machine_code.hpp"

namespace lagrange {

namespace fs = std::filesystem;

namespace {

// The model's name as a C identifier (the modelIdentifier, so the .so's name).
std::string c_identifier(const std::string& name) {
  std::string id;
  for (unsigned char ch : name) id += std::isalnum(ch) ? static_cast<char>(ch) : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "model_" + id;
  return id;
}

// A GUID from the SHA-256 of what the FMU is made of: the same model, the same GUID.
std::string guid_of(const std::string& text) {
  const std::string h = sha256_hex(text);
  return fmt::format("{{{}-{}-{}-{}-{}}}", h.substr(0, 8), h.substr(8, 4), h.substr(12, 4),
                     h.substr(16, 4), h.substr(20, 12));
}

// A private scratch directory, removed with everything in it at the end of the scope.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "lagrange-fmu-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw std::runtime_error("export --fmu: cannot create a temporary directory in " +
                               fs::temp_directory_path().string());
    path = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

std::string read_binary(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    throw std::runtime_error("export --fmu: cannot read " + path.string());
  return bytes;
}

// Each input's value at t = 0 with the parameters' defaults: the start of the FMI inputs.
std::vector<double> input_starts(const CompiledModel& cm) {
  if (cm.k == 0) return {};
  std::vector<double> in(cm.input_count(), 0.0), out(cm.inputs.num_outputs()),
      work(cm.inputs.work_size() + 1);
  std::copy(cm.parameter_defaults.begin(), cm.parameter_defaults.end(),
            in.begin() + static_cast<long>(cm.p_offset()));
  cm.inputs.eval(in.data(), out.data(), work.data());
  return {out.begin(), out.begin() + static_cast<long>(cm.k)};
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char ch : s)
    out += ch == '<' ? "&lt;" : ch == '>' ? "&gt;" : ch == '&' ? "&amp;" : std::string(1, ch);
  return out;
}

std::string documentation(const fmu::Description& d, const std::string& equations) {
  return fmt::format(
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{0}</title></head><body>\n"
      "<h1>{0}</h1>\n<p>FMI 2.0 FMU exported by <code>lagrange export --fmu</code>. States: the "
      "coordinates and their velocities. Co-Simulation integrates with DOP853, as lagrange "
      "simulate does "
      "(tolerances fmu.rtol, fmu.atol) and projects onto the constraints after each step; Model "
      "Exchange gives the derivatives of the KKT solve with Baumgarte rate fmu.baumgarte_alpha. "
      "The equations are in <a href=\"equations.txt\">equations.txt</a>.</p>\n<pre>{1}</pre>\n"
      "</body></html>\n",
      html_escape(d.model_name), html_escape(equations));
}

}  // namespace

FmuOptions fmu_options(const Model& model) {
  FmuOptions o;
  o.model_name = model.name;
  o.alpha = model.stabilization.alpha.value_or(kDefaultBaumgarte);
  o.project = model.stabilization.project;
  o.rtol = model.simulate.rtol;
  o.atol = model.simulate.atol;
  o.t_end = model.simulate.t_end;
  o.output_step = model.simulate.output_step;
  return o;
}

void export_fmu(const CompiledModel& cm, const FmuOptions& o, const std::string& path) {
  if (o.fmi_type != "cs" && o.fmi_type != "me" && o.fmi_type != "both")
    throw std::invalid_argument(
        fmt::format("--fmi-type: expected cs, me or both, got '{}'", o.fmi_type));
  const ScratchDir scratch;
  const fs::path sources = scratch.path / "sources";
  export_c(cm, sources.string());
  fmu::Description d;
  d.model_name = o.model_name.empty() ? "lagrange model" : o.model_name;
  d.identifier = c_identifier(d.model_name);
  d.model_exchange = o.fmi_type != "cs";
  d.co_simulation = o.fmi_type != "me";
  d.alpha = o.alpha;
  d.project = o.project;
  d.rtol = o.rtol;
  d.atol = o.atol;
  d.t_end = o.t_end;
  d.output_step = o.output_step;
  d.input_starts = input_starts(cm);
  d.guid = guid_of(read_binary(sources / "lagrange_model.c") + fmu::model_description(cm, d));

  std::vector<std::pair<std::string, std::string>> entries{
      {"modelDescription.xml", fmu::model_description(cm, d)}};
  std::vector<std::pair<std::string, std::string>> source_files{
      {"lagrange_model.h", read_binary(sources / "lagrange_model.h")},
      {"lagrange_model.c", read_binary(sources / "lagrange_model.c")},
      {"lagrange_fmu_model.h", fmu::model_header(cm, d)}};
  for (const fmu::File& f : fmu::files()) source_files.emplace_back(f.name, f.text);
  for (const auto& [name, text] : source_files)
    std::ofstream(sources / name, std::ios::binary) << text;

  const fs::path so = scratch.path / (d.identifier + ".so");
  try {
    run_c_compiler(resolve_c_compiler(o.compiler),
                   {"-std=c99", "-O2", "-fPIC", "-shared", "-fvisibility=hidden",
                    "-ffp-contract=off", "-fno-math-errno", "-I", sources.string(), "-o",
                    so.string(), (sources / "lagrange_fmu.c").string(), "-lm"},
                   (scratch.path / "cc.log").string());
  } catch (const MachineCodeError& e) {
    throw std::runtime_error(fmt::format("export --fmu: compiling the FMU's binary: {}", e.what()));
  }
  entries.emplace_back("binaries/linux64/" + d.identifier + ".so", read_binary(so));
  for (auto& [name, text] : source_files) entries.emplace_back("sources/" + name, std::move(text));
  entries.emplace_back("documentation/index.html", documentation(d, o.equations));
  entries.emplace_back("documentation/equations.txt", o.equations);
  write_file_atomically(path, zip_stored(entries));
}

}  // namespace lagrange
