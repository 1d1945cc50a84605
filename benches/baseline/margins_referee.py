"""40-digit referee for the margins of 0.5/(s^3 + 2s^2 + s + 0.5) at T = 1 ms, K = 0.99, B = 0.

The exact ZOH of P(s) by partial fractions, Pd(z) = (1 - 1/z) * sum_i r_i z/(z - e^{p_i T})
with r_i the residues of P(s)/s, evaluated in mpmath at 40 digits: the gain crossover
(|L| = 1) with its phase margin and the phase crossover (Im L = 0) with its gain margin.
Run: python3 benches/baseline/margins_referee.py (needs mpmath). Used by
crates/hapstab-cli/tests/cli/margins.rs.
"""
import mpmath as mp
mp.mp.dps=40
T=mp.mpf('1e-3'); K=mp.mpf('0.99')
ps=mp.polyroots([1,2,1,mp.mpf('0.5'),0], maxsteps=200, extraprec=200)
dPs=lambda s: 4*s**3+6*s**2+2*s+mp.mpf('0.5')
res=[mp.mpf('0.5')/dPs(p) for p in ps]
def L(th):
    z=mp.exp(1j*th)
    return K*(1-1/z)*sum(r*z/(z-mp.exp(p*T)) for r,p in zip(res,ps))
print(ps, L(mp.mpf('0.00064')))
g=lambda th: abs(L(th))-1
th=mp.findroot(g, (mp.mpf('0.0006'), mp.mpf('0.00068')), solver='anderson')
print('wgc rad/s', th/T, 'pm', 180+mp.degrees(mp.arg(L(th))))
thp=mp.findroot(lambda t: mp.im(L(t)), (mp.mpf('0.00099'), mp.mpf('0.00101')), solver='anderson')
print('wpc', thp/T, 'gm', -1/mp.re(L(thp)))
