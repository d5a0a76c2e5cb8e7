"""The seed's energy-replenishment study (fixed chargers and mobile chargers): so far its
theoretical bounds (bounds.py, ``swarmvm bounds energy``)."""
