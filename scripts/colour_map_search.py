#!/usr/bin/env python3
"""The search that picked the colours of DOP853, Vern9, Tsit5 and RK5 in src/widgets/colors.rs
(issue 21: slide 13 showed "three pinks"). Candidates: Okabe-Ito and Paul Tol hues (bright,
vibrant, muted), each darkened or lightened towards black or white in steps of 10 % until it
reaches 3:1 against both themes\x27 backgrounds and plot panels. Euler, midpoint, RK4 and the
typo\x27s pink stay as they are (slides name them). Greedy swaps from 60 seeded random starts
maximise the least CIEDE2000 difference, for normal vision, between methods that share slide
13 or 14, subject to every such pair keeping a protanope\x27s and a
deuteranope\x27s difference (Machado et al. 2009) of at least 7.5. Plain Python, no packages:
    python3 scripts/colour_map_search.py
"""
import math
def lin(s): return s/12.92 if s<=0.04045 else ((s+0.055)/1.055)**2.4
def unlin(l):
    l=min(max(l,0),1); return 12.92*l if l<=0.0031308 else 1.055*l**(1/2.4)-0.055
def lab(c):
    r,g,b=[lin(v) for v in c]
    x=0.4124564*r+0.3575761*g+0.1804375*b; y=0.2126729*r+0.7151522*g+0.072175*b; z=0.0193339*r+0.119192*g+0.9503041*b
    d=6/29
    f=lambda t: t**(1/3) if t>d**3 else t/(3*d*d)+4/29
    fx,fy,fz=f(x/0.95047),f(y),f(z/1.08883)
    return [116*fy-16,500*(fx-fy),200*(fy-fz)]
P=[[0.152286,1.052583,-0.204868],[0.114503,0.786281,0.099216],[-0.003882,-0.048116,1.051998]]
D=[[0.367322,0.860646,-0.227968],[0.280085,0.672501,0.047413],[-0.011820,0.042940,0.968881]]
def sim(c,m):
    if m is None: return c
    x=[lin(v) for v in c]
    return [unlin(sum(r[i]*x[i] for i in range(3))) for r in m]
def de00(p,q):
    l1,a1,b1=p;l2,a2,b2=q
    cb=0.5*(math.hypot(a1,b1)+math.hypot(a2,b2)); c7=cb**7
    g=0.5*(1-math.sqrt(c7/(c7+25**7)))
    a1p,a2p=(1+g)*a1,(1+g)*a2
    c1p,c2p=math.hypot(a1p,b1),math.hypot(a2p,b2)
    hue=lambda a,b: 0 if a==0 and b==0 else math.degrees(math.atan2(b,a))%360
    h1p,h2p=hue(a1p,b1),hue(a2p,b2)
    dl=l2-l1; dc=c2p-c1p
    if c1p*c2p==0: dh=0
    else:
        d=h2p-h1p
        dh=d-360 if d>180 else d+360 if d<-180 else d
    dH=2*math.sqrt(c1p*c2p)*math.sin(math.radians(dh)/2)
    lb=0.5*(l1+l2); cpb=0.5*(c1p+c2p)
    if c1p*c2p==0: hb=h1p+h2p
    elif abs(h1p-h2p)<=180: hb=0.5*(h1p+h2p)
    elif h1p+h2p<360: hb=0.5*(h1p+h2p+360)
    else: hb=0.5*(h1p+h2p-360)
    cos=lambda d: math.cos(math.radians(d))
    t=1-0.17*cos(hb-30)+0.24*cos(2*hb)+0.32*cos(3*hb+6)-0.20*cos(4*hb-63)
    dth=30*math.exp(-((hb-275)/25)**2)
    rc=2*math.sqrt(cpb**7/(cpb**7+25**7))
    sl=1+0.015*(lb-50)**2/math.sqrt(20+(lb-50)**2); sc=1+0.045*cpb; sh=1+0.015*cpb*t
    rt=-math.sin(math.radians(2*dth))*rc
    x,y,z=dl/sl,dc/sc,dH/sh
    return math.sqrt(x*x+y*y+z*z+rt*y*z)
def hexc(h): return [int(h[i:i+2],16)/255 for i in (1,3,5)]
from functools import lru_cache
VISION={None:None,'P':P,'D':D}
@lru_cache(None)
def de(a,b,v): return de00(lab(sim(hexc(a),VISION[v])),lab(sim(hexc(b),VISION[v])))
def lum(c): r,g,b=[lin(v) for v in c]; return 0.2126*r+0.7152*g+0.0722*b
def contrast(a,b):
    la,lb=lum(a),lum(b); return (max(la,lb)+0.05)/(min(la,lb)+0.05)
BACKGROUNDS=[hexc(h) for h in ('#161921','#1e222c','#fbf9f4','#f1eee6')]  # app::theme
def ok(c): return min(contrast(c,b) for b in BACKGROUNDS)>=3.0
def tohex(c): return '#%02X%02X%02X'%tuple(round(v*255) for v in c)
BASE={'OI orange':'#E69F00','OI sky':'#56B4E9','OI yellow':'#F0E442','OI rpurple':'#CC79A7',
'Tol blue':'#4477AA','Tol cyan':'#66CCEE','Tol green':'#228833','Tol yellow':'#CCBB44','Tol red':'#EE6677','Tol purple':'#AA3377','grey':'#BBBBBB',
'V blue':'#0077BB','V cyan':'#33BBEE','V teal':'#009988','V orange':'#EE7733','V red':'#CC3311','V magenta':'#EE3377',
'M indigo':'#332288','M cyan':'#88CCEE','M teal':'#44AA99','M green':'#117733','M olive':'#999933','M sand':'#DDCC77','M rose':'#CC6677','M wine':'#882255','M purple':'#AA4499','mid grey':'#888888'}
def candidates():
    out={}
    for n,h in BASE.items():
        c=hexc(h)
        for t in [0,0.1,0.2,0.3,0.4]:
            for tgt,tag in (([0,0,0],'darker'),([1,1,1],'lighter')):
                d=[round((v+(w-v)*t)*255)/255 for v,w in zip(c,tgt)]
                if ok(d): out.setdefault(tohex(d), f'{n} {tag} {t:.1f}')
        # and the nearest shade that reaches 3:1 (1 % steps towards black or white)
        for k in range(0,60):
            hit=[d for d in ([round((v+(w-v)*k/100)*255)/255 for v,w in zip(c,tgt)] for tgt in ([0,0,0],[1,1,1])) if ok(d)]
            if hit:
                out.setdefault(tohex(hit[0]), f'{n} nearest 3:1')
                break
    return out
FIXED=dict(euler='#D55E00',mid='#0072B2',rk4='#009C72',typo='#BE719C')
FREE=['dop853','vern9','tsit5','rk5']
SLIDES=[['euler','mid','rk4','typo','dop853','vern9'],['euler','mid','rk4','tsit5','dop853','vern9','rk5']]
PAIRS=sorted({(a,b) for s in SLIDES for i,a in enumerate(s) for b in s[i+1:]})
DICHROMAT_MIN=7.5
def score(m):
    normal=min(de(m[a],m[b],None) for a,b in PAIRS)
    dich=min(min(de(m[a],m[b],'P'),de(m[a],m[b],'D')) for a,b in PAIRS)
    return normal if dich>=DICHROMAT_MIN else dich-DICHROMAT_MIN-100
if __name__=='__main__':
    import random
    cand=candidates(); vals=list(cand)
    random.seed(1); best=(-1e9,None)
    for _ in range(60):
        m=dict(FIXED); m.update({r:random.choice(vals) for r in FREE}); cur=score(m)
        improved=True
        while improved:
            improved=False
            for r in FREE:
                for v in vals:
                    old=m[r]; m[r]=v; s=score(m)
                    if s>cur+1e-9: cur=s; improved=True
                    else: m[r]=old
        if cur>best[0]: best=(cur,dict(m))
    print('least normal-vision difference on a slide: %.1f'%best[0])
    for r in FREE: print(r, best[1][r], cand[best[1][r]])
    # Second stage, after radau5 took a cyan 3.4 from the sea blue above: Tsit5 alone on a
    # 16-level sRGB grid, ≥ 15 (normal) and ≥ 7.5 (dichromats) from slide 14's other lines and
    # ≥ 4 from every role of the map, best smallest difference (dichromats' counted twice).
    slide14=['#D55E00','#0072B2','#009C72','#707070','#857A47','#BB5C92']
    roles=slide14+['#A25179','#BE719C','#968951','#228833','#CC3311','#197C3A','#EE1199','#337777','#9C6B30','#1C8FB0','#B04381','#938C29','#6E62AA','#B87E00','#AA4499']
    grid=[]
    for h in ('#%02X%02X%02X'%(r*17,g*17,b*17) for r in range(16) for g in range(16) for b in range(16)):
        if not ok(hexc(h)): continue
        nm=min(de(h,x,None) for x in slide14)
        dc=min(min(de(h,x,'P'),de(h,x,'D')) for x in slide14)
        if nm>=15 and dc>=7.5 and min(de(h,x,None) for x in roles)>=4: grid.append((min(nm,2*dc),h))
    print('tsit5 (grid)', max(grid)[1])
