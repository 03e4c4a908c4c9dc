"""dhfield: the extended double-Hertz model of an adhesive elliptical contact.

Zini, de Rooij, Bazr Afshan Fadafan, Ismail & Schipper, Tribology Letters 66 (2018) 30,
doi:10.1007/s11249-017-0976-8, verified against a DC-FFT boundary-element solver.
"""
__version__ = "0.1.0"
PAPER_DOI = "10.1007/s11249-017-0976-8"
