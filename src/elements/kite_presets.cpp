// Published kite data for `preset:` (docs/model-language.md, "Kites").
//
// ap2: the Ampyx AP2 as parameterised in awebox (awebox/opts/kite_data/ampyx_data.py), citing
// Malz, Koenemann, Sieberling and Gros, "A reference model for airborne wind energy systems for
// optimization and control", Renewable Energy (2019), and Licitra et al. (2017) for the geometry.
// megawes: the TU Delft MegAWES aircraft (awebox/opts/kite_data/megawes_data.py, geometry from
// Eijkelhof and Schmehl, Renewable Energy 196 (2022) 137–150; the "VLM" derivative set).
// Both tables are in the standard body axes (x forward, y right, z down), angles in radians.

#include <fmt/format.h>

#include <stdexcept>

#include "elements/kite.hpp"

namespace lagrange::elements {

GiNaC::ex exact_decimal(const std::string& text) {
  std::string digits;
  long scale = 1;
  bool negative = false, point = false;
  for (char c : text) {
    if (c == '-') {
      negative = true;
    } else if (c == '.') {
      point = true;
    } else if (c >= '0' && c <= '9') {
      digits += c;
      if (point) scale *= 10;
    } else {
      throw std::logic_error("exact_decimal: not a decimal literal: " + text);
    }
  }
  const GiNaC::numeric value(std::stol(digits), scale);
  return negative ? GiNaC::ex(-value) : GiNaC::ex(value);
}

GiNaC::ex DerivativeTable::evaluate(const AeroInputs& in) const {
  const std::map<std::string, GiNaC::ex> inputs = {
      {"1", 1},       {"alpha", in.alpha}, {"beta", in.beta},   {"p", in.phat},   {"q", in.qhat},
      {"r", in.rhat}, {"da", in.aileron},  {"de", in.elevator}, {"dr", in.rudder}};
  GiNaC::ex sum = 0;
  for (const auto& [input, poly] : terms) {
    GiNaC::ex k = 0, power = 1;
    for (const auto& c : poly) {
      k += exact_decimal(c) * power;
      power *= in.alpha;
    }
    sum += k * inputs.at(input);
  }
  return sum;
}

namespace {

using Terms = std::vector<std::pair<std::string, std::vector<std::string>>>;

KitePreset ap2() {
  KitePreset k;
  k.name = "ap2";
  k.source =
      "Ampyx AP2 (awebox ampyx_data.py; Malz, Koenemann, Sieberling, Gros, Renewable Energy "
      "2019)";
  k.mass = exact_decimal("36.8");
  k.area = 3;
  k.span = exact_decimal("5.5");
  k.chord = k.area / k.span;
  k.aspect_ratio = k.span * k.span / k.area;
  k.cd0 = exact_decimal("0.0293");
  const GiNaC::ex jxz = exact_decimal("0.47");
  k.inertia = {Vec3{25, 0, jxz}, Vec3{0, 32, 0}, Vec3{jxz, 0, 56}};
  k.coefficients[0].terms = Terms{{"1", {"-0.0293"}},
                                  {"alpha", {"0.4784", "2.5549"}},
                                  {"q", {"-0.6029", "4.4124"}},
                                  {"de", {"-0.0106", "0.1115"}}};
  k.coefficients[1].terms = Terms{{"beta", {"-0.1855", "-0.0299", "0.0936"}},
                                  {"p", {"-0.1022", "-0.0140", "0.0496"}},
                                  {"r", {"0.1694", "0.1368"}},
                                  {"da", {"-0.0514", "-0.0024", "0.0579"}},
                                  {"dr", {"0.10325", "0.0268", "-0.1036"}}};
  k.coefficients[2].terms = Terms{{"1", {"-0.5526"}},
                                  {"alpha", {"-5.0676", "5.7736"}},
                                  {"q", {"-7.5560", "0.1251", "6.1486"}},
                                  {"de", {"-0.315", "-0.0013", "0.2923"}}};
  k.coefficients[3].terms = Terms{{"beta", {"-0.0630", "-0.0003", "0.0312"}},
                                  {"p", {"-0.5632", "-0.0247", "0.2813"}},
                                  {"r", {"0.1811", "0.6448"}},
                                  {"da", {"-0.2489", "-0.0087", "0.2383"}},
                                  {"dr", {"0.00436", "-0.0013"}}};
  k.coefficients[4].terms = Terms{{"1", {"-0.0307"}},
                                  {"alpha", {"-0.6027"}},
                                  {"q", {"-11.3022", "-0.0026", "5.2885"}},
                                  {"de", {"-1.0427", "-0.0061", "0.9974"}}};
  k.coefficients[5].terms = Terms{{"beta", {"0.0577", "-0.0849"}},
                                  {"p", {"-0.0565", "-0.9137"}},
                                  {"r", {"-0.0553", "0.0290", "0.0257"}},
                                  {"da", {"0.01903", "-0.1147"}},
                                  {"dr", {"-0.0404", "-0.0117", "0.04089"}}};
  return k;
}

KitePreset megawes() {
  KitePreset k;
  k.name = "megawes";
  k.source =
      "MegAWES (awebox megawes_data.py, VLM set; Eijkelhof and Schmehl, Renewable Energy 196 "
      "(2022))";
  k.mass = exact_decimal("6885.2");
  k.area = exact_decimal("150.45");
  k.span = exact_decimal("42.47");
  k.chord = k.area / k.span;
  k.aspect_ratio = k.span * k.span / k.area;
  k.cd0 = exact_decimal("0.046");
  k.inertia = {Vec3{exact_decimal("576800"), 0, 0}, Vec3{0, exact_decimal("81070"), 0},
               Vec3{0, 0, exact_decimal("650020")}};
  k.coefficients[0].terms = Terms{{"1", {"-0.046"}},
                                  {"alpha", {"0.5329", "3.6178"}},
                                  {"q", {"-0.1689", "3.1142", "-0.3229"}},
                                  {"de", {"-0.0203", "0.2281", "0.0541"}}};
  k.coefficients[1].terms = Terms{{"beta", {"-0.2056", "-0.1529", "-0.3609"}},
                                  {"p", {"0.0588", "0.3069", "-0.0109"}},
                                  {"r", {"0.0869", "0.0271", "-0.0541"}},
                                  {"da", {"0.0064", "-0.0365", "-0.0022"}},
                                  {"dr", {"0.1801", "0.0196", "-0.1724"}}};
  k.coefficients[2].terms = Terms{{"1", {"-0.8781"}},
                                  {"alpha", {"-4.7042", "0.0335"}},
                                  {"q", {"-5.9365", "-0.7263", "2.4422"}},
                                  {"de", {"-0.4867", "-0.007", "0.4642"}}};
  k.coefficients[3].terms = Terms{{"beta", {"-0.0101", "-0.1834", "0.0023"}},
                                  {"p", {"-0.4888", "-0.027", "0.092"}},
                                  {"r", {"0.1966", "0.5629", "-0.0498"}},
                                  {"da", {"-0.1972", "0.0574", "0.1674"}},
                                  {"dr", {"0.0077", "-0.0091", "-0.0092"}}};
  k.coefficients[4].terms = Terms{{"1", {"-0.065"}},
                                  {"alpha", {"-0.3306", "0.2245"}},
                                  {"q", {"-7.7531", "-0.003", "3.8925"}},
                                  {"de", {"-1.1885", "-0.0007", "1.1612"}}};
  k.coefficients[5].terms = Terms{{"beta", {"0.0385", "0.0001", "-0.0441"}},
                                  {"p", {"-0.0597", "-0.7602", "0.0691"}},
                                  {"r", {"-0.0372", "-0.0291", "-0.2164"}},
                                  {"da", {"0.0054", "-0.0425", "0.0354"}},
                                  {"dr", {"-0.0404", "-0.0031", "0.0385"}}};
  return k;
}

}  // namespace

const KitePreset* find_kite_preset(const std::string& name) {
  static const std::vector<KitePreset> presets = {ap2(), megawes()};
  for (const KitePreset& p : presets)
    if (p.name == name) return &p;
  return nullptr;
}

std::string kite_preset_names() {
  return "ap2, megawes";
}

}  // namespace lagrange::elements
