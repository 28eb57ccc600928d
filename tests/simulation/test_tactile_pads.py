"""TactilePads' reading of real contact surfaces, in both of Drake's representations, against
the plain per-element reading and the every-corner integral (benchmarks/pad_contact_reads.py),
on the fixed-input scene of tests/test_leaf_systems_pad_contact.py: a rigid block pressed
into the left pad across its whole width (so across its column edges) and two of its rows."""

import numpy as np
import pytest

from benchmarks.pad_contact_reads import per_element_surface_arrays
from tegrasp_drake.simulation.contact_pressure import every_corner_cell_integrals
from tegrasp_drake.simulation.tactile_pads import _pads_surfaces, pads_forces, surface_arrays
from tests.test_leaf_systems_pad_contact import _pressed_pad

REPRESENTATIONS = ["triangle", "polygon"]


def _held(representation: str):
    """(contact results, pad geometry ids, pad poses function) of the pressed block."""
    plant, pads, contacts, poses, _ = _pressed_pad(representation=representation)
    pad_list = [pads["left"], pads["right"]]
    X_WP = [poses[int(pad.body_index)] @ pad.X_BP for pad in pad_list]
    return contacts, [pad.geometry_id for pad in pad_list], lambda: X_WP


@pytest.mark.parametrize("representation", REPRESENTATIONS)
def test_the_surface_arrays_are_the_per_element_reading(representation):
    contacts, ids, poses = _held(representation)
    assert contacts.num_hydroelastic_contacts() == 1
    surface = contacts.hydroelastic_contact_info(0).contact_surface()
    assert surface.is_triangle() == (representation == "triangle")
    assert surface.num_faces() > 20  # a real surface of many faces
    for read, reference in zip(surface_arrays(surface), per_element_surface_arrays(surface),
                               strict=True):
        np.testing.assert_array_equal(read, reference)
    for pad, pad_reference in zip(
            _pads_surfaces(contacts, ids, poses),
            _pads_surfaces(contacts, ids, poses, per_element_surface_arrays), strict=True):
        for surface_read, surface_reference in zip(pad, pad_reference, strict=True):
            for read, reference in zip(surface_read, surface_reference, strict=True):
                np.testing.assert_array_equal(read, reference)


@pytest.mark.parametrize("representation", REPRESENTATIONS)
def test_taxel_forces_equal_the_per_element_reading_and_every_corner_integral(
        representation):
    contacts, ids, poses = _held(representation)
    forces = np.concatenate(pads_forces(contacts, ids, poses))
    reference = np.concatenate(pads_forces(
        contacts, ids, poses, read_surface=per_element_surface_arrays,
        cell_integrals=every_corner_cell_integrals))
    assert np.count_nonzero(forces[:12] > 0.01 * forces.max()) >= 6  # two rows, 3 columns
    np.testing.assert_allclose(forces, reference, rtol=1e-12, atol=1e-12 * reference.max())
