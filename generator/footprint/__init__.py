"""The footprint report: flash and RAM of linked images (``measure``), worst-case stack
(``stack``), cycles per step in an emulator (``cycles``, ``cycles_m4``), budgets and limits
(``budget``), deltas against a baseline (``delta``), and the report's forms (``report``,
``chart``)."""
