#pragma once
// `peridot import-peridigm`: a Peridigm input deck (YAML, or Teuchos parameter-list XML) translated into a Peridot
// deck. Discretizations: Exodus meshes (a body per element block), text point files (converted: Peridigm's columns
// are x y z block volume, Peridot's x y z volume block) and PdQuickGrid boxes (a lattice); rectangular bond filters
// as pre-cracks. Materials Elastic (lps), Elastic Plastic [Hardening] (lps_plastic), Viscoelastic (lps_viscoelastic),
// Elastic Correspondence (correspondence, hypoelastic) and Elastic Bond Based (pmb); damage model Critical Stretch;
// blocks with their horizons; node sets (text files of node ids, converted to 0-based ids, or the mesh's own node
// sets); prescribed displacements, initial displacements and velocities, body forces with their expressions; the
// Verlet and quasi-static solvers; Exodus output. What has no equivalent is named in a note, never dropped silently.
#include <string>
#include <utility>
#include <vector>

namespace peridot {

struct PeridigmImport {
  std::string deck;                 ///< the Peridot deck, YAML text
  std::vector<std::string> notes;   ///< what was left out or assumed, each naming the Peridigm key
  /// Files the deck refers to, converted from Peridigm's (point files, node-set id files): path and contents.
  std::vector<std::pair<std::string, std::string>> files;
};

/// Translates the Peridigm deck at `path` for a Peridot deck to be written at `output_path` (file names in the
/// result are relative to its folder; converted files are named after it). Throws InputError at the Peridigm
/// deck's file:line:col for what cannot be translated: a file that is not a Peridigm deck, a discretization or
/// a reference that cannot be resolved.
PeridigmImport import_peridigm(const std::string& path, const std::string& output_path);

}  // namespace peridot
