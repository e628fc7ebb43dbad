"""The four-row roller guide of Soleimanian, Mohammadpour and Ahmadian (2020), Proc IMechE
Part J (paper 000): ``carriage`` (eq. 1b), ``roller_law`` (eq. 2), ``four_rows`` (preload, row
loads and quasi-static stiffness, eqs. 3 and 6-14), ``contact_model`` (the contact FMUs'
continuous-time model and output contract), ``film`` (eqs. 4-5), ``greenwood_tripp`` (eqs. 16-17
and 24-26), ``hertz_line``, ``friction`` (eqs. 24-31) and ``ehl`` (the numerical mixed-EHL line
contact, eqs. 15-31). Its parameter tables are in :mod:`..papers.soleimanian2020`.
"""
