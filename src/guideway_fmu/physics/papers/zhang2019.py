"""Zhang, Wang and Le (2019), Modeling and experiment on contact stiffness and accuracy analysis
of ball linear guide feed unit, J Harbin Inst Tech: the few values it gives (angles in degrees,
as printed). It prints no geometry of its feed unit: the FeedUnitErrors FMU's layout, balls
and preload are the project's example (docs/feed-unit.md).
"""

# Section 3 (Fig. 12): the contact angles the paper computes
CONTACT_ANGLE_DEG = 45.0  # alpha [deg] at rest, where the lateral and vertical stiffness are equal
CONTACT_ANGLE_RANGE_DEG = (30.0, 65.0)  # the initial contact angles of Fig. 12 [deg]
