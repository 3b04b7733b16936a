/* docs/tutorials/pendulum_main.c: calls the C that `lagrange export --c` wrote for the
   pendulum, as a controller on a microcontroller would, and prints the acceleration. */
#include <math.h>
#include <stdio.h>

#include "lagrange_model.h"

int main(void) {
  const double p[LAGRANGE_NP] = {1.0, 1.0, 9.81}; /* m, l, g: the order of the header */
  const double q[LAGRANGE_NQ] = {0.5}, v[LAGRANGE_N] = {0.0};
  double qdot[LAGRANGE_NQ], a[LAGRANGE_N], lambda[1];
  if (lagrange_dynamics(0.0, q, v, NULL, p, 0.0, qdot, a, lambda) != 0) return 1;
  printf("theta_ddot = %.10f (-(g/l) sin(theta) = %.10f)\n", a[0], -9.81 * sin(0.5));
  return 0;
}
