"""The trust boundary: what every verb and runtime loader shares to take input and give output.

Bad input becomes one line (``errors``), user text is escaped per output context (``escape``,
``terminal``), files are written as a transaction (``output``), the API checks its arguments by
one rule per parameter (``arguments``), and SIGTERM unwinds a verb as an exception does
(``termination``)."""
