"""swarmvm: compiles synthesised supervisors into table-driven VMs for swarm robots.

The pipeline, one module per stage: load (load_supervisor, load_automata) -> validate (inside
the loaders, with errors.InputError) -> canonicalise (canonical) -> build tables (tables) ->
serialise (image) -> render (render, targets)."""

__version__ = "0.1.0"
