/* Spring forces of the reference model: the loop of reference/forces.py's
   numpy version, for speed (the springs are three quarters of its time).
   E = k2 dr^2 + k3 dr^3 + k4 dr^4 per bond, dr = |x_j - x_i| - r0. */

#include <math.h>

double spring_forces(int n_bonds, const int *ends, const double *r0, const double *k2,
                     const double *k3, const double *k4, const double *x, int n_atoms,
                     double *force)
{
  double energy = 0.0;
  for (int a = 0; a < 2 * n_atoms; a++) force[a] = 0.0;
  for (int b = 0; b < n_bonds; b++) {
    const int i = ends[2 * b], j = ends[2 * b + 1];
    const double dx = x[2 * j] - x[2 * i];
    const double dy = x[2 * j + 1] - x[2 * i + 1];
    const double r = sqrt(dx * dx + dy * dy);
    const double dr = r - r0[b];
    energy += dr * dr * (k2[b] + dr * (k3[b] + dr * k4[b]));
    const double tension = dr * (2.0 * k2[b] + dr * (3.0 * k3[b] + dr * 4.0 * k4[b])) / r;
    force[2 * i] += tension * dx;
    force[2 * i + 1] += tension * dy;
    force[2 * j] -= tension * dx;
    force[2 * j + 1] -= tension * dy;
  }
  return energy;
}
