"""FMUs of the roller guide of Soleimanian et al. (2020): VerticalDynamics, the contact FMUs
(ContactDryHertz, ContactEHL) and the friction FMUs (FrictionMixedEHL, FrictionCoulomb)."""
