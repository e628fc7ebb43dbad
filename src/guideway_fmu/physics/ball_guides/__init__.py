"""Linear ball guides: ``hertz_point`` (a ball in a circular-arc groove), ``carriage_5dof``
(Wu et al. 2012, paper 001), ``feed_unit`` and ``milling_force`` (Zhang, Wang and Le 2019, paper
004, with a mechanistic end-mill force), ``ball_row`` and ``ball_to_ball`` (Lin, Duan and
Okwudire 2019, paper 003). Their parameter tables are in :mod:`..papers`.
"""
