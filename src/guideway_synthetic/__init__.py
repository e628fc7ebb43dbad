"""Test and benchmark support, not part of the product: generators of measured runs that hide
a known effect, for the discrepancy workflow of guideway_fmu.diagnose to be measured on.

- truth / truth_vertical: the first generators (horizontal drive, vertical response);
- second_truth / second_truth_vertical: generators written independently of the first ones
  and of the workflow's candidate laws (other rigs, motions, noise colours, record layouts);
- trials: a truth run diagnosed end to end in a child process, summarised.
"""
