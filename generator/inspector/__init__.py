"""The inspector: canonical traces read back (``trace``), the packed form of the runs a page
holds (``encoding``), and the one offline page that replays them against the supervisors
(``page``)."""
