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

   Velocity Verlet closes step n with a half kick and opens step n+1 with
   another, two passes over v and f with nothing between them but the
   end-of-step fixes and the output. When none of them reads the atoms at
   step n, the closing kick waits and is done in the opening pass, v += dtfm
   f twice in a row: the same operations in the same order, so the same bits,
   in one pass over the arrays instead of two (docs/benchmarks/loop_rate.md).
------------------------------------------------------------------------- */

#include "fix_nve_2d.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "memory.h"
#include "modify.h"
#include "output.h"
#include "update.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

// LAMMPS keeps x, v and f as contiguous rows of three doubles (memory->grow
// of a 2-d array): read them as such, with no row pointer per atom, and tell
// the compiler that they do not overlap
struct Vec3 {
  double x, y, z;
};
static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");

// KICKS half kicks of v (each v += dtfm f, in order), then, if DRIFT,
// x += dtv v; dtfm from the per-atom mass (RMASS) or the per-type table
template <int KICKS, bool DRIFT, bool RMASS>
void update_atoms(Vec3 *__restrict x, Vec3 *__restrict v, const Vec3 *__restrict f,
                  const double *__restrict rmass, const double dtf,
                  const double *__restrict dtfm_type, const int *__restrict type,
                  const int *__restrict mask, const int bit, const int nlocal, const double dtv)
{
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    const double dtfm = RMASS ? dtf / rmass[i] : dtfm_type[type[i]];
    for (int k = 0; k < KICKS; k++) {
      v[i].x += dtfm * f[i].x;
      v[i].y += dtfm * f[i].y;
    }
    if (DRIFT) {
      x[i].x += dtv * v[i].x;
      x[i].y += dtv * v[i].y;
    }
  }
}

// the loop for a closing kick (kicks 1, no drift), an opening one (1, drift)
// or a deferred closing kick with the opening one (2, drift)
template <bool RMASS>
void update_by_mass(Vec3 *x, Vec3 *v, const Vec3 *f, const double *rmass, const double dtf,
                    const double *dtfm_type, const int *type, const int *mask, const int bit,
                    const int nlocal, const double dtv, const int kicks, const bool drift)
{
  if (!drift)
    update_atoms<1, false, RMASS>(x, v, f, rmass, dtf, dtfm_type, type, mask, bit, nlocal, dtv);
  else if (kicks == 1)
    update_atoms<1, true, RMASS>(x, v, f, rmass, dtf, dtfm_type, type, mask, bit, nlocal, dtv);
  else
    update_atoms<2, true, RMASS>(x, v, f, rmass, dtf, dtfm_type, type, mask, bit, nlocal, dtv);
}

}    // namespace

/* ---------------------------------------------------------------------- */

FixNVE2d::FixNVE2d(LAMMPS *lmp, int narg, char **arg) :
    FixNVE(lmp, narg, arg), dtfm_type(nullptr), ntypes(0), every(nullptr), nevery_fixes(0),
    pending(false), fuse(false)
{
  if (domain->dimension != 2) error->all(FLERR, "Fix nve/2d requires dimension 2");
}

/* ---------------------------------------------------------------------- */

FixNVE2d::~FixNVE2d()
{
  memory->destroy(dtfm_type);
  memory->destroy(every);
}

/* ----------------------------------------------------------------------
   true for an end-of-step fix that may read x or v; fix area/barrier reads
   the angle style's counts only, and acts every step: counted, it would
   never let a closing half kick be deferred
------------------------------------------------------------------------- */

bool FixNVE2d::reads_atoms(Fix *fix)
{
  if (!(fix->setmask() & FixConst::END_OF_STEP)) return false;
  return strcmp(fix->style, "area/barrier") != 0;
}

/* ----------------------------------------------------------------------
   the end-of-step fixes of this run and how often each acts
------------------------------------------------------------------------- */

void FixNVE2d::init()
{
  FixNVE::init();
  memory->destroy(every);
  every = nullptr;
  nevery_fixes = 0;
  for (int i = 0; i < modify->nfix; i++)
    if (reads_atoms(modify->fix[i])) nevery_fixes++;
  if (nevery_fixes) memory->create(every, nevery_fixes, "nve/2d:every");
  int n = 0;
  for (int i = 0; i < modify->nfix; i++)
    if (reads_atoms(modify->fix[i])) every[n++] = modify->fix[i]->nevery;
  pending = false;
  // rRESPA calls final_integrate at every inner level: never deferred there
  fuse = !utils::strmatch(update->integrate_style, "^respa");
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

/* ----------------------------------------------------------------------
   true if anything may read x or v after this step's final_integrate: the
   run's last step, output (thermo, dump, restart), an end-of-step fix
------------------------------------------------------------------------- */

bool FixNVE2d::velocities_read(bigint step) const
{
  if (step >= update->laststep || step == output->next) return true;
  for (int i = 0; i < nevery_fixes; i++)
    if (every[i] <= 0 || step % every[i] == 0) return true;
  return false;
}

/* ----------------------------------------------------------------------
   kicks half kicks (1 or 2), then the drift if drift
------------------------------------------------------------------------- */

void FixNVE2d::move_atoms(int kicks, bool drift)
{
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;
  if (nlocal == 0) return;
  double *const rmass = atom->rmass;
  if (!rmass) set_dtfm();
  Vec3 *const x = reinterpret_cast<Vec3 *>(atom->x[0]);
  Vec3 *const v = reinterpret_cast<Vec3 *>(atom->v[0]);
  const Vec3 *const f = reinterpret_cast<const Vec3 *>(atom->f[0]);
  const int *const type = atom->type;
  const int *const mask = atom->mask;
  const int bit = groupbit;
  if (rmass)
    update_by_mass<true>(x, v, f, rmass, dtf, dtfm_type, type, mask, bit, nlocal, dtv, kicks,
                         drift);
  else
    update_by_mass<false>(x, v, f, rmass, dtf, dtfm_type, type, mask, bit, nlocal, dtv, kicks,
                          drift);
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::initial_integrate(int /*vflag*/)
{
  move_atoms(pending ? 2 : 1, true);
  pending = false;
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::final_integrate()
{
  if (!fuse || velocities_read(update->ntimestep))
    move_atoms(1, false);
  else
    pending = true;
}

/* ----------------------------------------------------------------------
   a run that ends early (timer timeout) leaves no kick undone
------------------------------------------------------------------------- */

void FixNVE2d::post_run()
{
  if (pending) move_atoms(1, false);
  pending = false;
}
