/* Co-Simulation stepping cost of an exported FMU (docs/fmu.md, "Speed"): instantiates the FMU's
   binary, initialises it and times fmi2DoStep over [0, t_end] with communication step h, without
   reading outputs (the importer's own overhead left out).
   cc -O2 -I src/io/fmi2 bench/fmu_step_time.c -o fmu_step_time -ldl
   ./fmu_step_time unzipped/binaries/linux64/<id>.so '<guid>' T_END H */
#define _POSIX_C_SOURCE 199309L
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
  (void)env, (void)status, (void)category;
  fprintf(stderr, "%s: %s\n", name, message);
}

#define LOAD(type, name) type* name = (type*)dlsym(lib, #name)

int main(int argc, char** argv) {
  void* lib;
  fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
  struct timespec a, b;
  double t_end, h, t = 0.0;
  fmi2Component c;
  if (argc != 5) return 2;
  lib = dlopen(argv[1], RTLD_NOW);
  if (!lib) return 3;
  t_end = atof(argv[3]);
  h = atof(argv[4]);
  {
    LOAD(fmi2InstantiateTYPE, fmi2Instantiate);
    LOAD(fmi2SetupExperimentTYPE, fmi2SetupExperiment);
    LOAD(fmi2EnterInitializationModeTYPE, fmi2EnterInitializationMode);
    LOAD(fmi2ExitInitializationModeTYPE, fmi2ExitInitializationMode);
    LOAD(fmi2DoStepTYPE, fmi2DoStep);
    c = fmi2Instantiate("bench", fmi2CoSimulation, argv[2], "", &cb, fmi2False, fmi2False);
    if (!c || fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) != fmi2OK ||
        fmi2EnterInitializationMode(c) != fmi2OK || fmi2ExitInitializationMode(c) != fmi2OK)
      return 4;
    clock_gettime(CLOCK_MONOTONIC, &a);
    while (t < t_end - 1e-12) {
      if (fmi2DoStep(c, t, h, fmi2True) != fmi2OK) return 5;
      t += h;
    }
    clock_gettime(CLOCK_MONOTONIC, &b);
  }
  printf("%.4f s for %.6g s simulated: %.4g ms per simulated second\n",
         (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec), t_end,
         1e3 * ((b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec)) / t_end);
  return 0;
}
