"""auszug: computational Gothic design.

From a symmetric top-view drawing to the 3D network of ogee curves of Gothic
microarchitecture (:mod:`auszug.microarch`), tracery windows (:mod:`auszug.tracery`),
meshes and solids of both (:mod:`auszug.meshing`), file formats (:mod:`auszug.formats`),
the command line (:mod:`auszug.cli`) and the browser studio (:mod:`auszug.studio`), on
exact 2D curve geometry (:mod:`auszug.geometry`).
"""
