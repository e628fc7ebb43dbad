"""Raceway wear of a linear ball guide and the preload it costs (Zhang, Wang and Jiang,
fractal-creep wear, paper 002): ``creep`` (Carter's creep and adhesion areas), ``fractal``
(W-M surfaces and their contact) and ``raceway_wear`` (wear depth and preload over the running
distance). Its parameter table (the LG20 guide) is in :mod:`..papers.zhang_wang_jiang`.
"""
