/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Bond style harmonic/quartic, the spring of the workflow's MODEL.md:

     E = ka x^2 / 2 + kb x^4 / 4,   x = r - r0

   with r0, ka, kb per bond type. The same energy as bond_style class2 with
   K2 = ka/2, K3 = 0, K4 = kb/4, at about a third of the cost
   (docs/benchmarks/spring_cost.md). Bonds go in blocks: coordinate
   differences and coefficients are gathered into short contiguous arrays;
   the arithmetic, with its square root and division, runs as one loop of
   fixed length that the compiler turns into SIMD code; then the forces are
   added to the atoms. z is skipped in 2-D runs.
------------------------------------------------------------------------- */

#include "bond_harmonic_quartic.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neighbor.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

namespace {

// Flat views of atom->x / atom->f and neighbor->bondlist, which LAMMPS
// allocates as one contiguous block behind the row pointers; reading them
// this way saves a dependent pointer load per atom and per bond.
struct Vec3 {
  double x, y, z;
};
struct BondEntry {
  int i1, i2, type;
};
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
static_assert(sizeof(BondEntry) == 3 * sizeof(int), "BondEntry must be three packed ints");

// Bonds per block: the block's scratch arrays (11 kB) stay in L1, and a
// fixed trip count lets the compiler vectorise the arithmetic without a
// remainder loop (gcc's -O2 cost model requires that). 128 measured faster
// than 64 and 256.
constexpr int BLOCK = 128;

// Several x86-64 builds of the block arithmetic, the best one picked when the
// library loads: its square roots and divisions, the bulk of a spring's cost,
// run 2 (SSE2), 4 (AVX2) or 8 (AVX-512) bonds per instruction.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define HARMONIC_QUARTIC_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define HARMONIC_QUARTIC_CLONES
#endif

// One block of BLOCK bonds, from the coordinate differences and the
// coefficients gathered by the caller: the force on the first atom (fx, fy,
// fz), the force over distance fbond and, with EVFLAG, the energy. Fixed trip
// count, no branches, no aliasing: the compiler vectorises it (given
// -fno-math-errno, so that sqrt needs no errno check).
template <int EVFLAG, int THREE_D>
HARMONIC_QUARTIC_CLONES void block_forces(const double *__restrict dx, const double *__restrict dy,
                                          const double *__restrict dz, const double *__restrict r0,
                                          const double *__restrict ka, const double *__restrict kb,
                                          double *__restrict fx, double *__restrict fy,
                                          double *__restrict fz, double *__restrict fbond,
                                          double *__restrict ebond)
{
  for (int k = 0; k < BLOCK; k++) {
    double rsq = dx[k] * dx[k] + dy[k] * dy[k];
    if (THREE_D) rsq += dz[k] * dz[k];
    const double r = sqrt(rsq);
    const double dr = r - r0[k];
    const double dr2 = dr * dr;
    const double de = ka[k] * dr + kb[k] * (dr2 * dr);
    // at r = 0 the force vector (fb times a zero difference) is zero
    // whatever fb is; dividing by 1 there keeps the loop branch-free
    // (an == test, unlike >, raises no flag on NaN and so may be vectorised)
    const double fb = -de / (r + (r == 0.0));
    fx[k] = dx[k] * fb;
    fy[k] = dy[k] * fb;
    if (THREE_D) fz[k] = dz[k] * fb;
    if (EVFLAG) {
      fbond[k] = fb;
      ebond[k] = 0.5 * ka[k] * dr2 + 0.25 * kb[k] * (dr2 * dr2);
    }
  }
}

}    // namespace

/* ---------------------------------------------------------------------- */

BondHarmonicQuartic::BondHarmonicQuartic(LAMMPS *lmp) :
    Bond(lmp), r0(nullptr), ka(nullptr), kb(nullptr), param(nullptr)
{
  writedata = 1;
#ifdef BOND_HARMONIC_QUARTIC_BORN_MATRIX
  born_matrix_enable = 1;
#endif
}

/* ---------------------------------------------------------------------- */

BondHarmonicQuartic::~BondHarmonicQuartic()
{
  if (copymode) return;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(r0);
    memory->destroy(ka);
    memory->destroy(kb);
    memory->sfree(param);
  }
}

/* ---------------------------------------------------------------------- */

void BondHarmonicQuartic::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  // param is filled by init_style(); a bond_coeff between runs goes
  // through init() again before the next force call
  const int three_d = (domain->dimension == 3);
  const int newton = force->newton_bond;
  if (evflag) {
    if (newton) {
      if (three_d) eval<1, 1, 1>(0, neighbor->nbondlist);
      else eval<1, 1, 0>(0, neighbor->nbondlist);
    } else {
      if (three_d) eval<1, 0, 1>(0, neighbor->nbondlist);
      else eval<1, 0, 0>(0, neighbor->nbondlist);
    }
  } else {
    if (newton) {
      if (three_d) eval<0, 1, 1>(0, neighbor->nbondlist);
      else eval<0, 1, 0>(0, neighbor->nbondlist);
    } else {
      if (three_d) eval<0, 0, 1>(0, neighbor->nbondlist);
      else eval<0, 0, 0>(0, neighbor->nbondlist);
    }
  }
}

/* ----------------------------------------------------------------------
   forces (and with EVFLAG energy and virial) of bonds nfrom .. nto-1
------------------------------------------------------------------------- */

template <int EVFLAG, int NEWTON_BOND, int THREE_D>
void BondHarmonicQuartic::eval(int nfrom, int nto)
{
  if (nto <= nfrom) return;    // atom->x may not be allocated yet
  const Vec3 *const __restrict x = reinterpret_cast<const Vec3 *>(atom->x[0]);
  Vec3 *const __restrict f = reinterpret_cast<Vec3 *>(atom->f[0]);
  const BondEntry *const __restrict bonds =
      reinterpret_cast<const BondEntry *>(neighbor->bondlist[0]);
  const Param *const __restrict coeffs = param;
  const int nlocal = atom->nlocal;
  // Steps that want the global energy alone (a thermo or compute pe row, as
  // the impact deck's series every few steps): ev_tally's sum, in the same
  // order, without its per-bond bookkeeping of what is not wanted.
  const bool energy_only = EVFLAG && NEWTON_BOND && eflag_global && !eflag_atom && !vflag_either;

  alignas(64) double dx[BLOCK], dy[BLOCK], dz[BLOCK];
  alignas(64) double b_r0[BLOCK], b_ka[BLOCK], b_kb[BLOCK];
  alignas(64) double fx[BLOCK], fy[BLOCK], fz[BLOCK], fbond[BLOCK], ebond[BLOCK];

  for (int start = nfrom; start < nto; start += BLOCK) {
    const int m = (nto - start < BLOCK) ? nto - start : BLOCK;
    const BondEntry *const block = bonds + start;

    for (int k = 0; k < m; k++) {
      const Vec3 &a = x[block[k].i1];
      const Vec3 &b = x[block[k].i2];
      const Param &p = coeffs[block[k].type];
      dx[k] = a.x - b.x;
      dy[k] = a.y - b.y;
      if (THREE_D) dz[k] = a.z - b.z;
      b_r0[k] = p.r0;
      b_ka[k] = p.ka;
      b_kb[k] = p.kb;
    }
    // the unused tail of the last block: springs at rest, no force
    for (int k = m; k < BLOCK; k++) {
      dx[k] = 1.0;
      dy[k] = dz[k] = 0.0;
      b_r0[k] = 1.0;
      b_ka[k] = b_kb[k] = 0.0;
    }

    block_forces<EVFLAG, THREE_D>(dx, dy, dz, b_r0, b_ka, b_kb, fx, fy, fz, fbond, ebond);

    // LAMMPS lists an atom's bonds one after the other (first atom i1), so
    // the force on i1 is summed in registers over such a run: adding to
    // f[i1] bond by bond would chain each update to the store before it.
    int cur = block[0].i1;
    double ax = 0.0, ay = 0.0, az = 0.0;
    for (int k = 0; k < m; k++) {
      const int i1 = block[k].i1;
      const int i2 = block[k].i2;
      if (i1 != cur) {
        if (NEWTON_BOND || cur < nlocal) {
          f[cur].x += ax;
          f[cur].y += ay;
          if (THREE_D) f[cur].z += az;
        }
        cur = i1;
        ax = ay = az = 0.0;
      }
      ax += fx[k];
      ay += fy[k];
      if (THREE_D) az += fz[k];
      if (NEWTON_BOND || i2 < nlocal) {
        f[i2].x -= fx[k];
        f[i2].y -= fy[k];
        if (THREE_D) f[i2].z -= fz[k];
      }
      if (EVFLAG) {
        if (energy_only)
          energy += ebond[k];
        else
          ev_tally(i1, i2, nlocal, NEWTON_BOND, ebond[k], fbond[k], dx[k], dy[k], dz[k]);
      }
    }
    if (NEWTON_BOND || cur < nlocal) {
      f[cur].x += ax;
      f[cur].y += ay;
      if (THREE_D) f[cur].z += az;
    }
  }
}

/* ---------------------------------------------------------------------- */

void BondHarmonicQuartic::allocate()
{
  allocated = 1;
  const int n = atom->nbondtypes + 1;

  memory->create(r0, n, "bond:r0");
  memory->create(ka, n, "bond:ka");
  memory->create(kb, n, "bond:kb");
  param = static_cast<Param *>(memory->smalloc(sizeof(Param) * n, "bond:param"));
  memory->create(setflag, n, "bond:setflag");
  for (int i = 0; i < n; i++) {
    setflag[i] = 0;
    r0[i] = ka[i] = kb[i] = 0.0;
  }

}

/* ----------------------------------------------------------------------
   one bond_coeff line: N r0 ka kb (from the input or a data file)
------------------------------------------------------------------------- */

void BondHarmonicQuartic::coeff(int narg, char **arg)
{
  if (narg != 4)
    error->all(FLERR,
               "Incorrect args for bond coefficients: bond harmonic/quartic expects "
               "N r0 ka kb, got {} values",
               narg);
  if (!allocated) allocate();

  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nbondtypes, ilo, ihi, error);

  const double r0_one = utils::numeric(FLERR, arg[1], false, lmp);
  const double ka_one = utils::numeric(FLERR, arg[2], false, lmp);
  const double kb_one = utils::numeric(FLERR, arg[3], false, lmp);
  if (r0_one < 0.0) error->all(FLERR, "Bond harmonic/quartic: r0 must be >= 0, got {}", r0_one);
  if (ka_one < 0.0) error->all(FLERR, "Bond harmonic/quartic: ka must be >= 0, got {}", ka_one);
  if (kb_one < 0.0) error->all(FLERR, "Bond harmonic/quartic: kb must be >= 0, got {}", kb_one);

  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    r0[i] = r0_one;
    ka[i] = ka_one;
    kb[i] = kb_one;
    setflag[i] = 1;
    count++;
  }
  if (count == 0)
    error->all(FLERR, "Incorrect args for bond coefficients: no bond type in {}", arg[0]);
}

/* ----------------------------------------------------------------------
   pack the coefficients for the force loop; runs before every run, so it
   also sees changes made through extract() (fix adapt)
------------------------------------------------------------------------- */

void BondHarmonicQuartic::init_style()
{
  for (int i = 1; i <= atom->nbondtypes; i++) {
    param[i].r0 = r0[i];
    param[i].ka = ka[i];
    param[i].kb = kb[i];
  }
}

/* ---------------------------------------------------------------------- */

double BondHarmonicQuartic::equilibrium_distance(int i)
{
  return r0[i];
}

/* ---------------------------------------------------------------------- */

void BondHarmonicQuartic::write_restart(FILE *fp)
{
  fwrite(&r0[1], sizeof(double), atom->nbondtypes, fp);
  fwrite(&ka[1], sizeof(double), atom->nbondtypes, fp);
  fwrite(&kb[1], sizeof(double), atom->nbondtypes, fp);
}

/* ---------------------------------------------------------------------- */

void BondHarmonicQuartic::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->nbondtypes;
  if (comm->me == 0) {
    utils::sfread(FLERR, &r0[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &ka[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &kb[1], sizeof(double), n, fp, nullptr, error);
  }
  MPI_Bcast(&r0[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&ka[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&kb[1], n, MPI_DOUBLE, 0, world);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

/* ----------------------------------------------------------------------
   17 significant digits: read_data gets back the very doubles, so springs
   written at rest are still at rest
------------------------------------------------------------------------- */

void BondHarmonicQuartic::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nbondtypes; i++)
    fprintf(fp, "%d %.17g %.17g %.17g\n", i, r0[i], ka[i], kb[i]);
}

/* ---------------------------------------------------------------------- */

double BondHarmonicQuartic::single(int type, double rsq, int /*i*/, int /*j*/, double &fforce)
{
  const double r = sqrt(rsq);
  const double dr = r - r0[type];
  const double dr2 = dr * dr;
  fforce = (r > 0.0) ? -(ka[type] * dr + kb[type] * (dr2 * dr)) / r : 0.0;
  return 0.5 * ka[type] * dr2 + 0.25 * kb[type] * (dr2 * dr2);
}

/* ---------------------------------------------------------------------- */

#ifdef BOND_HARMONIC_QUARTIC_BORN_MATRIX
void BondHarmonicQuartic::born_matrix(int type, double rsq, int /*i*/, int /*j*/, double &du,
                                      double &du2)
{
  const double dr = sqrt(rsq) - r0[type];
  du = ka[type] * dr + kb[type] * dr * dr * dr;
  du2 = ka[type] + 3.0 * kb[type] * dr * dr;
}
#endif

/* ---------------------------------------------------------------------- */

void *BondHarmonicQuartic::extract(const char *str, int &dim)
{
  dim = 1;
  if (strcmp(str, "r0") == 0) return (void *) r0;
  if (strcmp(str, "ka") == 0) return (void *) ka;
  if (strcmp(str, "kb") == 0) return (void *) kb;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

double BondHarmonicQuartic::memory_usage()
{
  const double n = atom->nbondtypes + 1;
  return Bond::memory_usage() + n * (3.0 * sizeof(double) + sizeof(Param));
}
