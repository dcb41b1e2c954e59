"""The Python side of fr_instructions.sh: K calls of System.frequency_response at 10⁴ points (argv[1] = K)."""
import sys, numpy as np, stochvib
k = int(sys.argv[1])
w = np.linspace(0.01, 100.0, 10_000)
car = stochvib.System.model("quarter-car", sprung_mass=300.0, unsprung_mass=40.0, suspension_stiffness=20e3, suspension_damping=1.5e3, tyre_stiffness=200e3)
acc = 0.0
for _ in range(k):
    acc += car.frequency_response(w)[0, 0, 5000].real
print(acc)
