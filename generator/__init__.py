"""swarmvm: compiles synthesised supervisors into table-driven VMs for swarm robots.

The pipeline, one subpackage per part (docs/architecture.md): read and validate (readers/,
every defect a boundary.errors.InputError) -> canonicalise, build tables, serialise the image
(compiler/) -> render a target (targets/, compiler.render); api.py is every verb as a typed
function, cli/ the command line over it."""

__version__ = "0.1.0"
