<?xml version="1.0" encoding="UTF-8"?>
<!-- CityGML 3.0 for tests/geometry/CityGmlTest.cpp: a flat-roofed house (12 x 10 m, 12 m tall)
     whose thematic surfaces are core:boundary / con:*Surface, whose lod2Solid names its walls'
     MultiSurface by xlink, with a bldg:buildingPart (4 x 4 m, 20 m tall); and two buildings
     whose lod1Solid is the part's again, by xlink (GML's reuse of a geometry): one names its
     shell inside a gml:Solid, the other the whole solid from the property itself. -->
<core:CityModel xmlns:core="http://www.opengis.net/citygml/3.0" xmlns:bldg="http://www.opengis.net/citygml/building/3.0" xmlns:con="http://www.opengis.net/citygml/construction/3.0" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:gen="http://www.opengis.net/citygml/generics/3.0" xmlns:xlink="http://www.w3.org/1999/xlink">
  <gml:boundedBy><gml:Envelope srsName="http://www.opengis.net/def/crs/EPSG/0/25833" srsDimension="3"/></gml:boundedBy>
  <core:cityObjectMember>
    <bldg:Building gml:id="house3">
      <core:genericAttribute><gen:StringAttribute><gen:name>tile</gen:name><gen:value> tile-3 </gen:value></gen:StringAttribute></core:genericAttribute>
      <core:boundary><con:WallSurface gml:id="house3_walls"><core:lod2MultiSurface><gml:MultiSurface gml:id="house3_walls_ms"><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>0 0 50 12 0 50 12 0 62 0 0 62 0 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 0 50 12 10 50 12 10 62 12 0 62 12 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 10 50 0 10 50 0 10 62 12 10 62 12 10 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>0 10 50 0 0 50 0 0 62 0 10 62 0 10 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></core:lod2MultiSurface></con:WallSurface></core:boundary>
      <core:boundary><con:RoofSurface gml:id="house3_roof"><core:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>0 0 62 12 0 62 12 10 62 0 10 62 0 0 62</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></core:lod2MultiSurface></con:RoofSurface></core:boundary>
      <core:boundary><con:GroundSurface gml:id="house3_ground"><core:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>0 0 50 0 10 50 12 10 50 12 0 50 0 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></core:lod2MultiSurface></con:GroundSurface></core:boundary>
      <core:lod2Solid><gml:Solid><gml:exterior><gml:Shell><gml:surfaceMember xlink:href="#house3_walls_ms"/><gml:surfaceMember xlink:href="#house3_roof"/><gml:surfaceMember xlink:href="#house3_ground"/></gml:Shell></gml:exterior></gml:Solid></core:lod2Solid>
      <bldg:buildingPart>
        <bldg:BuildingPart gml:id="house3_tower">
          <core:lod1Solid><gml:Solid gml:id="tower_solid"><gml:exterior><gml:Shell gml:id="tower_shell"><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 0 50 12 4 50 16 4 50 16 0 50 12 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 0 70 16 0 70 16 4 70 12 4 70 12 0 70</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 0 50 16 0 50 16 0 70 12 0 70 12 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>16 0 50 16 4 50 16 4 70 16 0 70 16 0 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>16 4 50 12 4 50 12 4 70 16 4 70 16 4 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList>12 4 50 12 0 50 12 0 70 12 4 70 12 4 50</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:Shell></gml:exterior></gml:Solid></core:lod1Solid>
        </bldg:BuildingPart>
      </bldg:buildingPart>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <bldg:Building gml:id="reuse">
      <core:lod1Solid><gml:Solid><gml:exterior xlink:href="#tower_shell"/></gml:Solid></core:lod1Solid>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <bldg:Building gml:id="reuse_by_property">
      <core:lod1Solid xlink:href="#tower_solid"/>
    </bldg:Building>
  </core:cityObjectMember>
</core:CityModel>
