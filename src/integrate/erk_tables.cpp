#include "integrate/erk_tables.hpp"

#include <arkode/arkode_butcher_erk.h>

#include <iterator>

namespace lagrange::integration {

namespace {

// SUNDIALS names them NAME_stages_embedding_order. FEHLBERG_13_7_8 meets every order condition
// up to 8 (tests/integrate/test_erk_coefficients.cpp); ARKodeButcherTable_CheckOrder checks only
// up to order 6 and reports 6 for any higher-order table, and it ran at order 6 only while the
// first-same-as-last reuse (arkode_erk.cpp) took its last stage for the next step's first.
const ErkTable kTables[] = {
    {"heun-euler", ARKODE_HEUN_EULER_2_1_2, 2},
    {"bogacki-shampine", ARKODE_BOGACKI_SHAMPINE_4_2_3, 3},
    {"zonneveld", ARKODE_ZONNEVELD_5_3_4, 4},
    {"sayfy-aburub", ARKODE_SAYFY_ABURUB_6_3_4, 4},
    {"cash-karp", ARKODE_CASH_KARP_6_4_5, 5},
    {"fehlberg", ARKODE_FEHLBERG_6_4_5, 5},
    {"dormand-prince", ARKODE_DORMAND_PRINCE_7_4_5, 5},
    {"verner65", ARKODE_VERNER_8_5_6, 6},
    {"fehlberg78", ARKODE_FEHLBERG_13_7_8, 8},
    {"verner87", ARKODE_ERK_NONE, 8, verner_8_7},
};

}  // namespace

const ErkTable* find_erk_table(const std::string& name) {
  for (const ErkTable& table : kTables)
    if (name == table.name) return &table;
  return nullptr;
}

const ErkTable& default_erk_table(double rtol) {
  // Not verner87: at equal error at the step ends it needs fewer evaluations than verner65 from
  // about 1e-7 down, but its long steps leave the samples to the interpolant, whose error is then
  // far above the steps' (docs/benchmarks.md, work–precision).
  return rtol >= 1e-5 ? *find_erk_table("dormand-prince") : *find_erk_table("verner65");
}

}  // namespace lagrange::integration
