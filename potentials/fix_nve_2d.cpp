/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Fix nve/2d: fix nve's velocity Verlet for a 2-D run, bit for bit: the
   same updates of x, y, vx, vy in the same order, with dtf / mass taken
   once per atom type instead of once per atom (the same quotient), and no
   z. Everything else (init, the time step, rRESPA) is fix nve's own. On
   the impact deck's scene fix nve was a quarter of the loop
   (docs/benchmarks/loop_floor.md). The arrays are read as rows of three
   doubles that do not overlap (as the bond style reads them), without a
   row pointer per atom: the same updates in the same order, in fewer
   instructions (docs/benchmarks/resolution_cost.md).
------------------------------------------------------------------------- */

#include "fix_nve_2d.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"

using namespace LAMMPS_NS;

namespace {

// LAMMPS keeps x, v and f as contiguous rows of three doubles (memory->grow
// of a 2-d array): read them as such, with no row pointer per atom, and tell
// the compiler that they do not overlap
struct Vec3 {
  double x, y, z;
};
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");

}    // namespace

/* ---------------------------------------------------------------------- */

FixNVE2d::FixNVE2d(LAMMPS *lmp, int narg, char **arg) :
    FixNVE(lmp, narg, arg), dtfm_type(nullptr), ntypes(0)
{
  if (domain->dimension != 2) error->all(FLERR, "Fix nve/2d requires dimension 2");
}

/* ---------------------------------------------------------------------- */

FixNVE2d::~FixNVE2d()
{
  memory->destroy(dtfm_type);
}

/* ----------------------------------------------------------------------
   dtf / mass per type, for runs with per-type masses
------------------------------------------------------------------------- */

void FixNVE2d::set_dtfm()
{
  if (atom->ntypes != ntypes) {
    ntypes = atom->ntypes;
    memory->destroy(dtfm_type);
    memory->create(dtfm_type, ntypes + 1, "nve/2d:dtfm_type");
  }
  for (int t = 1; t <= ntypes; t++) dtfm_type[t] = dtf / atom->mass[t];
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::initial_integrate(int /*vflag*/)
{
  Vec3 *const __restrict x = reinterpret_cast<Vec3 *>(atom->x[0]);
  Vec3 *const __restrict v = reinterpret_cast<Vec3 *>(atom->v[0]);
  const Vec3 *const __restrict f = reinterpret_cast<const Vec3 *>(atom->f[0]);
  const double *const __restrict rmass = atom->rmass;
  const int *const __restrict type = atom->type;
  const int *const __restrict mask = atom->mask;
  const int bit = groupbit;
  const double dt_v = dtv;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;
  if (nlocal == 0) return;

  if (rmass) {
    const double dt_f = dtf;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & bit) {
        const double dtfm = dt_f / rmass[i];
        v[i].x += dtfm * f[i].x;
        v[i].y += dtfm * f[i].y;
        x[i].x += dt_v * v[i].x;
        x[i].y += dt_v * v[i].y;
      }
  } else {
    set_dtfm();
    const double *const __restrict dtfm_t = dtfm_type;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & bit) {
        const double dtfm = dtfm_t[type[i]];
        v[i].x += dtfm * f[i].x;
        v[i].y += dtfm * f[i].y;
        x[i].x += dt_v * v[i].x;
        x[i].y += dt_v * v[i].y;
      }
  }
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::final_integrate()
{
  Vec3 *const __restrict v = reinterpret_cast<Vec3 *>(atom->v[0]);
  const Vec3 *const __restrict f = reinterpret_cast<const Vec3 *>(atom->f[0]);
  const double *const __restrict rmass = atom->rmass;
  const int *const __restrict type = atom->type;
  const int *const __restrict mask = atom->mask;
  const int bit = groupbit;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;
  if (nlocal == 0) return;

  if (rmass) {
    const double dt_f = dtf;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & bit) {
        const double dtfm = dt_f / rmass[i];
        v[i].x += dtfm * f[i].x;
        v[i].y += dtfm * f[i].y;
      }
  } else {
    set_dtfm();
    const double *const __restrict dtfm_t = dtfm_type;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & bit) {
        const double dtfm = dtfm_t[type[i]];
        v[i].x += dtfm * f[i].x;
        v[i].y += dtfm * f[i].y;
      }
  }
}
