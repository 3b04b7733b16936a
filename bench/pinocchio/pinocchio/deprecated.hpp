// Stand-in for Pinocchio's generated deprecation header (bench/pinocchio.sh).
#pragma once
#define PINOCCHIO_DEPRECATED __attribute__((deprecated))
#define PINOCCHIO_DEPRECATED_MESSAGE(message) __attribute__((deprecated(message)))
