"""What drives and measures a guide on a test rig: ``feed_motion`` (prescribed feed profiles,
among them the bi-harmonic fit of Soleimanian et al. 2020's rig, and replays of a record),
``horizontal`` (the drive force of a horizontal rig), ``force_table`` (a recorded force replayed)
and ``friction_laws`` (the friction effects the discrepancy workflow adds to a rig model).
"""
