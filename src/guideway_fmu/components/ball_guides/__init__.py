"""FMUs of the ball guides: BallCarriage5DOF (Wu et al. 2012), FeedUnitErrors and MillingForce
(Zhang, Wang and Le 2019), BallToBallFriction (Lin, Duan and Okwudire 2019)."""
