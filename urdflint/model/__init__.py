"""The parsed robot and its views: what a URDF says, with no knowledge of how it is checked.

The bottom layer: it imports nothing else of urdflint. Views that need a higher layer
(the run's settings, the Pinocchio model, loaded meshes) are provided to the
:class:`~urdflint.model.document.Document` by the engine (see ``document.provide``).
"""
