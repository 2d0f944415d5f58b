"""How far the cloth swings once the mouse lets go, against its stiffness: swing_study.py [out.png]"""
import pathlib, sys

import matplotlib
matplotlib.use("Agg")  # no display: a file
import matplotlib.pyplot as plt
import particles

cloth = pathlib.Path(__file__).resolve().parents[2] / "scenarios" / "cloth.yaml"
scales = [0.25, 0.5, 1, 2, 4]  # × the cloth's own springs, 25 N/m at the top to 1 N/m at the bottom
swings = []
for scale in scales:
    springs = {"grids[0].springs.structural.ks": f"[{25 * scale}, {scale}]", "dt": 0.0025}  # RK4 stays stable
    sim = particles.Simulation(particles.Scenario.load(cloth, set=springs), threads=1)
    corner = sim.particle_index("cloth[24][12]")  # the bottom row's middle, where the mouse grabs
    rest_x, largest = sim.positions[corner, 0], 0.0
    sim.advance(3.5)  # the mouse lets go at t = 3.5 s
    while sim.time < 10.0 - 1e-9:
        sim.advance(0.02)
        largest = max(largest, abs(sim.positions[corner, 0] - rest_x))
    swings.append(largest)
    print(f"springs × {scale:<5} largest swing after release: {largest:.3f} m")
plt.semilogx(scales, swings, "o-", base=2)
plt.xlabel("spring constant, × the cloth's (25 N/m at the top)")
plt.ylabel("largest swing after release, m")
plt.title("The cloth's swing against its stiffness")
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "swing.png", dpi=120)
