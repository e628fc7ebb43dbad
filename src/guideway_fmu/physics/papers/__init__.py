"""Each paper's parameter tables, the one home of their values (SI units unless a name says
otherwise); the project's readings of what a paper leaves open sit with it, marked as such.

* ``soleimanian2020``: Soleimanian, Mohammadpour and Ahmadian (2020), the lubricated four-row
  roller guideway (Tables 1-4, the rig);
* ``wu2012``: Wu et al. (2012), the 5-DOF ball-guide carriage (Tables 1-2);
* ``zhang_wang_jiang``: Zhang, Wang and Jiang, fractal-creep raceway wear of the LG20 guide
  (Table 1);
* ``lin2019``: Lin, Duan and Okwudire (2019), ball-to-ball contact friction (Tables 1-2);
* ``zhang2019``: Zhang, Wang and Le (2019), the four-slider feed unit.

The modules hold plain constants and import nothing of the package, so importing one costs
nothing. A value written again elsewhere in the package fails
tests/physics/test_paper_tables.py.
"""
