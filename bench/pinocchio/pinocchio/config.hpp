// Stand-in for the config header that Pinocchio's CMake generates, so that bench/pinocchio_aba.cpp
// can use Pinocchio 3.7 header-only from its public source (bench/pinocchio.sh).
#pragma once
#define PINOCCHIO_MAJOR_VERSION 3
#define PINOCCHIO_MINOR_VERSION 7
#define PINOCCHIO_PATCH_VERSION 0
#define PINOCCHIO_VERSION "3.7.0"
#define PINOCCHIO_DLLAPI
#define PINOCCHIO_LOCAL
#define PINOCCHIO_EXPLICIT_INSTANTIATION_DECLARATION_DLLAPI
#define PINOCCHIO_EXPLICIT_INSTANTIATION_DEFINITION_DLLAPI
#define PINOCCHIO_VERSION_AT_LEAST(major, minor, patch)                                    \
  (PINOCCHIO_MAJOR_VERSION > major ||                                                      \
   (PINOCCHIO_MAJOR_VERSION >= major &&                                                    \
    (PINOCCHIO_MINOR_VERSION > minor ||                                                    \
     (PINOCCHIO_MINOR_VERSION >= minor && PINOCCHIO_PATCH_VERSION >= patch))))
