"""FMUs of the test rigs: FeedKinematics (prescribed feed), HorizontalRig, ForceTable and the
friction FMUs the discrepancy workflow adds to a rig model (Stribeck, Dahl, ...)."""
