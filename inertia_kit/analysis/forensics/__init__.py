"""
Forensics: why a declared inertia tensor disagrees with its link's geometry.

Each hypothesis is a known slip that turns the right tensor into the declared one, tested by
undoing the slip on the declared values and comparing the result with the geometry's tensor
(declared mass, uniform density, link frame, about the COM). One module per hypothesis holds
its search and its wording:

- ``other_point`` (IN060): the tensor is about another point (the link origin, a joint origin,
  a mesh's origin, or a point solved for when no mass inside the geometry could have the
  declared tensor) instead of the COM: ``declared = I_com + m (|d|² E - d dᵀ)``;
- ``flipped_signs`` (IN061): the products of inertia have the opposite sign convention
  (``ixy = +∫xy dm``);
- ``other_axes`` (IN062): the tensor is written in the axes of another frame (a shape's own
  axes, an axis permutation, the geometry's principal axes) without ``<inertial><origin rpy>``;
- ``unit_slip`` (IN063): the tensor in g·m², kg·mm², kg·cm², lb·in², … (or the inverse
  conversion), or the mass in grams;
- ``transposed`` (IN064): the six values transcribed into the wrong attributes.

The shared machinery: ``measure`` (the deviation between tensors and the tolerances that decide
what explains the numbers), ``candidate`` (the candidate type every hypothesis subclasses, the
case it is tested on, its :class:`~inertia_kit.analysis.forensics.candidate.Wording`),
``diagnosis`` (``diagnose``: every hypothesis searched, the simplest fit chosen) and ``links``
(a link's diagnosis, with its reference points and frames named).

Entry points
------------
``links.diagnose_link(link) -> Diagnosis | None``
    A link's diagnosis: against its collision geometry, else its visual one; ``None`` when the
    tensor agrees with either or nothing explains it. ``inertia-fill --fix invalid`` writes its
    ``corrected`` values.
``links.diagnose_basis(link, basis, loose=False)``
    The same against one of ``link.bases``; ``loose=True`` is IN020's "likely" note.
``links.explain(link, code)``
    What the forensic rule ``code`` (e.g. ``IN060``, whose hypothesis is ``AboutPoint``) reports
    about a link.
``diagnosis.diagnose(declared, expected, ...)``
    The pure test of one declared value against one geometry-derived value.
``measure.deviation(tensor, reference)``
    The measure: the largest relative difference of moments about any axis.
"""
