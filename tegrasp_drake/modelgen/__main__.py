"""Regenerates the model files in models/ from the generators (run from the repository root)."""

import pathlib
import sys

from tegrasp_drake.modelgen.jaco2_sdf import jaco2_sdf
from tegrasp_drake.modelgen.pad_mesh import PAD_REFINEMENTS, pad_vtk
from tegrasp_drake.modelgen.robotiq_linkage_sdf import robotiq_linkage_sdf
from tegrasp_drake.modelgen.robotiq_sdf import robotiq_sdf
from tegrasp_drake.modelgen.table_sdf import table_sdf
from tegrasp_drake.rig.files import write_atomically

GENERATED = {
    "jaco2/j2n6s300.sdf": jaco2_sdf,
    "robotiq_2f85/robotiq_2f85_tactile.sdf": robotiq_sdf,
    "robotiq_2f85/robotiq_2f85_linkage.sdf": robotiq_linkage_sdf,
    "table/table.sdf": table_sdf,
    # The pads' finer meshes (contact_geometry.pad_refinement): one file per level.
    **{f"robotiq_2f85/pad_refined_{k}.vtk": (lambda k=k: pad_vtk(k))
       for k in PAD_REFINEMENTS if k},
}

# How the generated kinds start (write_atomically's `start`): an SDFormat file's XML
# declaration (every generator writes one), a legacy VTK file's identifying first line (VTK
# file formats, "Simple Legacy Formats": "# vtk DataFile Version x.x").
FILE_STARTS = {".sdf": b"<?xml", ".vtk": b"# vtk DataFile"}


def main(models_dir: pathlib.Path) -> None:
    for relative, make in GENERATED.items():
        path = models_dir / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomically(path, make(), start=FILE_STARTS[path.suffix])
        print(f"wrote {path}")


if __name__ == "__main__":
    main(pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "models"))
