/* The arithmetic floor of an impact's step: the scene's springs and velocity
   Verlet in a plain loop, no contact, no neighbour lists, no fixes
   (bench/loop_floor.py builds and runs it).

     loop_floor scene.data dt steps final.txt

   Reads a data file of builder/lammps_data.py (atom_style bond, 2-D, bond
   style harmonic/quartic: one bond type per spring, coefficients r0 ka kb),
   moves every atom not held (molecule 3 is held, as fix nve's group "mobile"
   leaves it), and prints the loop's seconds. final.txt gets the atoms'
   positions by id, to check the loop against LAMMPS's. Masses are 1. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static char line[4096];

/* The next line that starts the section ``name``, or exit. */
static void find_section(FILE *in, const char *name)
{
  size_t length = strlen(name);
  while (fgets(line, sizeof line, in))
    if (strncmp(line, name, length) == 0) {
      fgets(line, sizeof line, in); /* the blank line after the title */
      return;
    }
  fprintf(stderr, "loop_floor: no %s section\n", name);
  exit(2);
}

static long header_count(FILE *in, const char *what)
{
  long count = 0;
  rewind(in);
  while (fgets(line, sizeof line, in)) {
    char word[64], word2[64];
    int fields = sscanf(line, "%ld %63s %63s", &count, word, word2);
    if (fields == 2 && strcmp(word, what) == 0) return count;
    if (fields == 3 && strcmp(word, what) == 0 && strcmp(word2, "types") != 0) return count;
  }
  fprintf(stderr, "loop_floor: no count of %s\n", what);
  exit(2);
}

/* V = ka dr^2 / 2 + kb dr^4 / 4 per spring, dr = r - r0. */
static void forces(long m, const int *ends, const double *r0, const double *ka,
                   const double *kb, const double *x, long n, double *f)
{
  memset(f, 0, 2 * n * sizeof *f);
  for (long b = 0; b < m; b++) {
    const int i = ends[2 * b], j = ends[2 * b + 1];
    const double dx = x[2 * i] - x[2 * j], dy = x[2 * i + 1] - x[2 * j + 1];
    const double r = sqrt(dx * dx + dy * dy), dr = r - r0[b];
    const double fbond = -(ka[b] + kb[b] * dr * dr) * dr / r;
    f[2 * i] += fbond * dx, f[2 * i + 1] += fbond * dy;
    f[2 * j] -= fbond * dx, f[2 * j + 1] -= fbond * dy;
  }
}

int main(int argc, char **argv)
{
  if (argc != 5) {
    fprintf(stderr, "usage: loop_floor scene.data dt steps final.txt\n");
    return 2;
  }
  FILE *in = fopen(argv[1], "r");
  if (!in) {
    perror(argv[1]);
    return 2;
  }
  const double dt = atof(argv[2]);
  const long steps = atol(argv[3]);
  const long n = header_count(in, "atoms"), m = header_count(in, "bonds");

  double *x = calloc(2 * n, sizeof *x), *v = calloc(2 * n, sizeof *v);
  double *f = calloc(2 * n, sizeof *f);
  double *r0 = calloc(m, sizeof *r0), *ka = calloc(m, sizeof *ka), *kb = calloc(m, sizeof *kb);
  int *ends = calloc(2 * m, sizeof *ends), *moves = calloc(n, sizeof *moves);
  double *coeff = calloc(3 * m, sizeof *coeff);

  find_section(in, "Bond Coeffs");
  for (long k = 0; k < m; k++) {
    long type;
    double a, b, c;
    if (!fgets(line, sizeof line, in) || sscanf(line, "%ld %lf %lf %lf", &type, &a, &b, &c) != 4)
      return fprintf(stderr, "loop_floor: bad Bond Coeffs line\n"), 2;
    coeff[3 * (type - 1)] = a, coeff[3 * (type - 1) + 1] = b, coeff[3 * (type - 1) + 2] = c;
  }
  find_section(in, "Atoms");
  for (long k = 0; k < n; k++) {
    long id, mol, type;
    double px, py;
    if (!fgets(line, sizeof line, in) ||
        sscanf(line, "%ld %ld %ld %lf %lf", &id, &mol, &type, &px, &py) != 5)
      return fprintf(stderr, "loop_floor: bad Atoms line\n"), 2;
    x[2 * (id - 1)] = px, x[2 * (id - 1) + 1] = py, moves[id - 1] = mol != 3;
  }
  find_section(in, "Velocities");
  for (long k = 0; k < n; k++) {
    long id;
    double vx, vy;
    if (!fgets(line, sizeof line, in) || sscanf(line, "%ld %lf %lf", &id, &vx, &vy) != 3)
      return fprintf(stderr, "loop_floor: bad Velocities line\n"), 2;
    v[2 * (id - 1)] = vx, v[2 * (id - 1) + 1] = vy;
  }
  find_section(in, "Bonds");
  for (long k = 0; k < m; k++) {
    long id, type, i, j;
    if (!fgets(line, sizeof line, in) ||
        sscanf(line, "%ld %ld %ld %ld", &id, &type, &i, &j) != 4)
      return fprintf(stderr, "loop_floor: bad Bonds line\n"), 2;
    ends[2 * k] = i - 1, ends[2 * k + 1] = j - 1;
    r0[k] = coeff[3 * (type - 1)], ka[k] = coeff[3 * (type - 1) + 1];
    kb[k] = coeff[3 * (type - 1) + 2];
  }
  fclose(in);

  struct timespec start, stop;
  clock_gettime(CLOCK_MONOTONIC, &start);
  forces(m, ends, r0, ka, kb, x, n, f); /* as LAMMPS's set-up does */
  for (long step = 0; step < steps; step++) {
    for (long i = 0; i < n; i++)
      if (moves[i]) {
        v[2 * i] += 0.5 * dt * f[2 * i], v[2 * i + 1] += 0.5 * dt * f[2 * i + 1];
        x[2 * i] += dt * v[2 * i], x[2 * i + 1] += dt * v[2 * i + 1];
      }
    forces(m, ends, r0, ka, kb, x, n, f);
    for (long i = 0; i < n; i++)
      if (moves[i]) v[2 * i] += 0.5 * dt * f[2 * i], v[2 * i + 1] += 0.5 * dt * f[2 * i + 1];
  }
  clock_gettime(CLOCK_MONOTONIC, &stop);
  printf("%.9f\n", (stop.tv_sec - start.tv_sec) + 1e-9 * (stop.tv_nsec - start.tv_nsec));

  FILE *out = fopen(argv[4], "w");
  if (!out) {
    perror(argv[4]);
    return 2;
  }
  for (long i = 0; i < n; i++) fprintf(out, "%ld %.17g %.17g\n", i + 1, x[2 * i], x[2 * i + 1]);
  fclose(out);
  return 0;
}
