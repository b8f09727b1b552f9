"""Cases of the DMA bearing (``family = "dma"``): friction torque of a cageless ball bearing, dynamically."""
