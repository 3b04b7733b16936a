// Stand-in for Pinocchio's generated warning header (bench/pinocchio.sh).
#pragma once
#define PINOCCHIO_WARNING(message)
