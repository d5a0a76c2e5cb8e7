"""Reproductions of the seed's studies on swarmvm's VMs (installed as ``swarmvm.studies``).

Each study is a subpackage (``drone_delivery``; ``energy`` later) with its model, engines,
metrics, sweep and plots; :mod:`swarmvm.studies.cli` gives them the ``sim``, ``sweep`` and
``plot`` command groups of the ``swarmvm`` command line."""
