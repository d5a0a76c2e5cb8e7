"""The ``swarmvm`` command line: click options and printing over :mod:`swarmvm.api`, nothing else
(``commands``), and what it shares with the studies' verbs (``options``)."""
