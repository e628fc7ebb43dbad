"""The equations, in SI units and without FMI, grouped by the system they describe.

* ``roller_guide``: the four-row roller guide of Soleimanian, Mohammadpour and Ahmadian (2020):
  the carriage's vertical dynamics, the roller law, the four rows, the film, the
  Greenwood-Tripp asperities, boundary and viscous friction and the numerical mixed EHL;
* ``ball_guides``: Hertz point contact and the ball-guide models of Wu et al. (2012, 5-DOF
  carriage), Zhang, Wang and Le (2019, feed unit and its cutting force) and Lin, Duan and
  Okwudire (2019, ball row and ball-to-ball friction);
* ``wear``: Zhang, Wang and Jiang's fractal-creep raceway wear and preload loss;
* ``rigs``: what drives or measures a guide on a test rig: prescribed feed motions, the
  horizontal drive rig, a replayed force table and the friction laws the discrepancy workflow
  adds to a rig;
* ``papers``: each paper's parameter tables, the one home of their values;
* shared: ``dynamics`` (the continuous-time model every FMU and the reference step),
  ``checks`` (argument checks with named errors) and ``roots`` (bounded root finding whose
  failure names what was solved for).
"""
