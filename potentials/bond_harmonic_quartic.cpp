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
   (docs/benchmarks/spring_cost.md). One plain loop over the bond list,
   with z skipped in 2-D runs. A blocked, vectorised form (gather, SIMD
   arithmetic, scatter; 43cb672 and before, made on an AMD EPYC) ran the
   impact's loop 12 % slower on the Intel Xeon of
   docs/benchmarks/loop_floor.md (2026-11-25).

   The workflow gives every bond its own type (its own r0), so a loop that
   reads the bond list and then each bond's coefficients streams 36 bytes
   per bond, which at 150,000 atoms no longer stays in cache. The loop
   reads a packed copy of the list instead: both atoms and r0 per bond,
   and a 2-byte row into a table of the few distinct (ka, kb), 18 bytes
   per bond, remade whenever LAMMPS rebuilds its lists. The same numbers
   in the same order: the forces are bit for bit those of the plain loop
   (docs/benchmarks/resolution_cost.md).
------------------------------------------------------------------------- */

#include "bond_harmonic_quartic.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"

#include <cmath>
#include <cstring>
#include <map>
#include <utility>

using namespace LAMMPS_NS;

namespace {

struct Vec3 {
  double x, y, z;
};
struct BondEntry {
  int i1, i2, type;
};
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
static_assert(sizeof(BondEntry) == 3 * sizeof(int), "BondEntry must be three packed ints");
// rows of the stiffness table a bond's 2-byte index can name
constexpr int MAX_STIFFNESS = 65536;

}    // namespace

/* ---------------------------------------------------------------------- */

BondHarmonicQuartic::BondHarmonicQuartic(LAMMPS *lmp) :
    Bond(lmp), r0(nullptr), ka(nullptr), kb(nullptr), param(nullptr), packed(nullptr),
    packed_class(nullptr), npacked(0), maxpacked(0), packed_ncalls(-1), packed_source(nullptr),
    type_class(nullptr), stiffness(nullptr), nstiffness(0), want_packed(1), use_packed(0)
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
  memory->sfree(packed);
  memory->sfree(packed_class);
  memory->sfree(stiffness);
  memory->destroy(type_class);
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
  if (use_packed) {
    if (neighbor->ncalls != packed_ncalls || neighbor->bondlist != packed_source ||
        neighbor->nbondlist != npacked)
      pack();
    if (evflag) {
      if (newton) {
        if (three_d) eval_packed<1, 1, 1>(0, npacked);
        else eval_packed<1, 1, 0>(0, npacked);
      } else {
        if (three_d) eval_packed<1, 0, 1>(0, npacked);
        else eval_packed<1, 0, 0>(0, npacked);
      }
    } else {
      if (newton) {
        if (three_d) eval_packed<0, 1, 1>(0, npacked);
        else eval_packed<0, 1, 0>(0, npacked);
      } else {
        if (three_d) eval_packed<0, 0, 1>(0, npacked);
        else eval_packed<0, 0, 0>(0, npacked);
      }
    }
    return;
  }
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

  for (int n = nfrom; n < nto; n++) {
    const int i1 = bonds[n].i1;
    const int i2 = bonds[n].i2;
    const Param &p = coeffs[bonds[n].type];
    const double dx = x[i1].x - x[i2].x;
    const double dy = x[i1].y - x[i2].y;
    const double dz = THREE_D ? x[i1].z - x[i2].z : 0.0;
    double rsq = dx * dx + dy * dy;
    if (THREE_D) rsq += dz * dz;
    const double r = sqrt(rsq);
    const double dr = r - p.r0;
    const double dr2 = dr * dr;
    const double fbond = r > 0.0 ? -(p.ka * dr + p.kb * (dr2 * dr)) / r : 0.0;

    if (NEWTON_BOND || i1 < nlocal) {
      f[i1].x += dx * fbond;
      f[i1].y += dy * fbond;
      if (THREE_D) f[i1].z += dz * fbond;
    }
    if (NEWTON_BOND || i2 < nlocal) {
      f[i2].x -= dx * fbond;
      f[i2].y -= dy * fbond;
      if (THREE_D) f[i2].z -= dz * fbond;
    }
    if (EVFLAG) {
      const double ebond = 0.5 * p.ka * dr2 + 0.25 * p.kb * (dr2 * dr2);
      if (energy_only)
        energy += ebond;
      else
        ev_tally(i1, i2, nlocal, NEWTON_BOND, ebond, fbond, dx, dy, dz);
    }
  }
}

/* ----------------------------------------------------------------------
   the same as eval(), from the packed list: the same numbers, the same order
------------------------------------------------------------------------- */

template <int EVFLAG, int NEWTON_BOND, int THREE_D>
void BondHarmonicQuartic::eval_packed(int nfrom, int nto)
{
  if (nto <= nfrom) return;
  const Vec3 *const __restrict x = reinterpret_cast<const Vec3 *>(atom->x[0]);
  Vec3 *const __restrict f = reinterpret_cast<Vec3 *>(atom->f[0]);
  const Packed *const __restrict bonds = packed;
  const unsigned short *const __restrict cls = packed_class;
  const Stiffness *const __restrict k = stiffness;
  const int nlocal = atom->nlocal;
  const bool energy_only = EVFLAG && NEWTON_BOND && eflag_global && !eflag_atom && !vflag_either;

  for (int n = nfrom; n < nto; n++) {
    const int i1 = bonds[n].i1;
    const int i2 = bonds[n].i2;
    const Stiffness &s = k[cls[n]];
    const double dx = x[i1].x - x[i2].x;
    const double dy = x[i1].y - x[i2].y;
    const double dz = THREE_D ? x[i1].z - x[i2].z : 0.0;
    double rsq = dx * dx + dy * dy;
    if (THREE_D) rsq += dz * dz;
    const double r = sqrt(rsq);
    const double dr = r - bonds[n].r0;
    const double dr2 = dr * dr;
    const double fbond = r > 0.0 ? -(s.ka * dr + s.kb * (dr2 * dr)) / r : 0.0;

    if (NEWTON_BOND || i1 < nlocal) {
      f[i1].x += dx * fbond;
      f[i1].y += dy * fbond;
      if (THREE_D) f[i1].z += dz * fbond;
    }
    if (NEWTON_BOND || i2 < nlocal) {
      f[i2].x -= dx * fbond;
      f[i2].y -= dy * fbond;
      if (THREE_D) f[i2].z -= dz * fbond;
    }
    if (EVFLAG) {
      const double ebond = 0.5 * s.ka * dr2 + 0.25 * s.kb * (dr2 * dr2);
      if (energy_only)
        energy += ebond;
      else
        ev_tally(i1, i2, nlocal, NEWTON_BOND, ebond, fbond, dx, dy, dz);
    }
  }
}

/* ----------------------------------------------------------------------
   the packed list from LAMMPS's bond list
------------------------------------------------------------------------- */

void BondHarmonicQuartic::pack()
{
  const int n = neighbor->nbondlist;
  if (n > maxpacked) {
    maxpacked = n + n / 8 + 1;
    memory->sfree(packed);
    memory->sfree(packed_class);
    packed = static_cast<Packed *>(memory->smalloc(sizeof(Packed) * maxpacked, "bond:packed"));
    packed_class = static_cast<unsigned short *>(
        memory->smalloc(sizeof(unsigned short) * maxpacked, "bond:packed_class"));
  }
  const BondEntry *const bonds = n ? reinterpret_cast<const BondEntry *>(neighbor->bondlist[0])
                                   : nullptr;
  for (int m = 0; m < n; m++) {
    const int t = bonds[m].type;
    packed[m].i1 = bonds[m].i1;
    packed[m].i2 = bonds[m].i2;
    packed[m].r0 = param[t].r0;
    packed_class[m] = static_cast<unsigned short>(type_class[t]);
  }
  npacked = n;
  packed_ncalls = neighbor->ncalls;
  packed_source = neighbor->bondlist;
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
   bond_style harmonic/quartic [packed yes|no]: no reads the bond list and
   each type's coefficients at every step (the benchmarks' "before")
------------------------------------------------------------------------- */

void BondHarmonicQuartic::settings(int narg, char **arg)
{
  if (narg == 0) return;
  if (narg != 2 || strcmp(arg[0], "packed") != 0)
    error->all(FLERR, "Illegal bond_style harmonic/quartic command: expects [packed yes|no]");
  if (strcmp(arg[1], "yes") == 0) want_packed = 1;
  else if (strcmp(arg[1], "no") == 0) want_packed = 0;
  else error->all(FLERR, "Illegal bond_style harmonic/quartic command: packed must be yes or no");
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
  const int ntypes = atom->nbondtypes;
  for (int i = 1; i <= ntypes; i++) {
    param[i].r0 = r0[i];
    param[i].ka = ka[i];
    param[i].kb = kb[i];
  }

  // the distinct (ka, kb) of the types, for the packed list; a fix that
  // changes bonds during a run (bond/break, bond/create, bond/swap, ...)
  // may rebuild the bond list without rebuilding the neighbour lists, so
  // the style then reads the bond list itself
  memory->destroy(type_class);
  memory->create(type_class, ntypes + 1, "bond:type_class");
  std::map<std::pair<double, double>, int> rows;
  type_class[0] = -1;
  for (int i = 1; i <= ntypes; i++) {
    auto found = rows.emplace(std::make_pair(ka[i], kb[i]), (int) rows.size());
    type_class[i] = found.first->second;
  }
  nstiffness = (int) rows.size();
  use_packed = want_packed && (nstiffness <= MAX_STIFFNESS);
  for (int i = 0; i < modify->nfix; i++)
    if (strncmp(modify->fix[i]->style, "bond/", 5) == 0) use_packed = 0;
  memory->sfree(stiffness);
  stiffness = static_cast<Stiffness *>(
      memory->smalloc(sizeof(Stiffness) * (nstiffness ? nstiffness : 1), "bond:stiffness"));
  for (const auto &row : rows) stiffness[row.second] = {row.first.first, row.first.second};
  // coefficients may have changed: pack again at the next force call
  packed_ncalls = -1;
  npacked = 0;
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
  return Bond::memory_usage() + n * (3.0 * sizeof(double) + sizeof(Param) + sizeof(int)) +
      (double) maxpacked * (sizeof(Packed) + sizeof(unsigned short)) +
      (double) nstiffness * sizeof(Stiffness);
}
