"""The OpenSwarm drone-delivery study (seed: "Optimising swarm behaviours through online
learning"; docs/studies/drone-delivery.md): a fleet of delivery drones whose logic is the
uav.yaml supervisor on the generated Python VM and whose bidding decision is the learned
classifier of docs/learning.md, simulated event by event (or tick by tick, for validation).

Modules: params (Table 2), energy (equations 13-15), orders, fleet (policies and their NumPy
mirror), controller (the generated VM), auction (winner rules), world (one tick), engine
(the two engines), metrics, sweep, plots. Importing the package itself loads nothing heavy, so
the command line starts without NumPy."""
